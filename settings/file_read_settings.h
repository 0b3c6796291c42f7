// FileReadSettings: what a file does not settle and a reader needs: an .amc's frame rate,
// a glTF/FBX clip and its sampling, a BVH skeleton's unit, a marker file's axes and scale
// relative to the skeleton, and which points of a C3D are markers. Declared once: the
// command line's flags (for every command that reads such files), the config keys and the
// Python keywords of the readers (read_motion, info, subject_from_files, read_markers).
// MotionReadOptionsOf / MarkerReadOptionsOf turn them into the readers' own options.
#ifndef MOCAPSOLVE_SETTINGS_FILE_READ_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_FILE_READ_SETTINGS_H_

#include <string>

#include "io/marker_file.h"
#include "io/motion_file.h"
#include "settings/option.h"

namespace mocapsolve {

struct FileReadSettings {
  double amc_fps = 120.0;           // Frame rate of .amc files (they store none; CMU: 120).
  std::string animation;            // glTF/FBX clip: name or index; "" = the first.
  double sample_fps = 0.0;          // glTF/FBX sampling; 0 = the key rate when uniform, else 30.
  std::string skeleton_units;       // Unit of a skeleton whose file states none: mm, cm, m, in.
  std::string axes = "x,y,z";       // Marker file axes -> skeleton axes (ParseAxes).
  double marker_scale = 0.0;        // Marker units -> skeleton units; 0 = from the files' units.
  bool include_model_outputs = false;  // C3D: model outputs read as markers.
  std::string subject_prefix;       // C3D of several subjects: whose points are read.
  std::string ignore_markers;       // Comma-separated labels read as missing in every frame.
};

const OptionGroup<FileReadSettings>& FileReadSettingOptions();

// The motion reader's options (io/motion_file.h) from these; `skeleton_path` is the .asf
// an .amc needs ("" when none).
MotionFileOptions MotionReadOptionsOf(const FileReadSettings& settings, const std::string& skeleton_path);
// The marker reader's options (io/marker_file.h) from these.
MarkerReadOptions MarkerReadOptionsOf(const FileReadSettings& settings);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_FILE_READ_SETTINGS_H_
