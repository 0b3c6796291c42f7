// CalibrateSettings: the options of calibrating a subject from a solved motion and its
// markers (`mocapsolve calibrate`, Python's calibrate()) besides the marker file's mapping
// (--axes, --marker_scale, common to every command that reads markers): which joints the
// markers ride on, how marker frames match motion frames, and which markers are kept.
// Declared once; the CLI's flags and Python's keywords. The calibration: tasks/calibrate_task.h.
#ifndef MOCAPSOLVE_SETTINGS_CALIBRATE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_CALIBRATE_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct CalibrateSettings {
  std::string attach = "auto";  // auto, or a marker set .json whose joints are kept.
  int frame_offset = 0;         // Marker frame = motion frame + frame_offset.
  int min_valid_frames = 2;     // Markers valid in fewer matched frames are left out.
  // Finish with fit_skeleton's refit (the calibrated subject as its template, on the same
  // markers, its defaults): lengths and offsets self-consistent with our own per-frame solve
  // instead of the given motion's poses. The subject only; --out's marker set stays the
  // calibration's, on the given skeleton.
  bool refit = false;
};

const OptionGroup<CalibrateSettings>& CalibrateSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_CALIBRATE_SETTINGS_H_
