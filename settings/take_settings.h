// TakeSettings: a pipeline take's name, whether its points are labelled first, and the
// filter of its solved motion, and the frame windows a long take runs in. Declared once:
// pipeline (and a batch manifest's per-take options).
#ifndef MOCAPSOLVE_SETTINGS_TAKE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_TAKE_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct TakeSettings {
  std::string take_name;  // The characters' new animation; "" = the marker file's stem.
  int filter_levels = 0;  // Laplacian-pyramid bands dropped from the solved motion; 0 = none.
  // Labelling the take's points first (pipeline/take_labelling.h): "auto" when the file
  // lacks some of the subject's labels, "always", or "never" (the file's labels as they are).
  std::string label = "auto";
  // A take longer than window_frames runs window by window (pipeline/take_windows.h), each
  // window's stages on its frames plus window_context_frames each side, so its memory is
  // bounded by the window, not the take.
  int window_frames = 18000;
  int window_context_frames = 600;
  // Frames on each side of a seam between two windows over which their motions (the solve,
  // each character's) cross-fade (pipeline/window_seam_blend.h); 0 = joined edge to edge.
  int window_seam_blend_frames = 60;
};

const OptionGroup<TakeSettings>& TakeSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_TAKE_SETTINGS_H_
