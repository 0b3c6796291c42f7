// FileSettings: the files a command reads and writes, named as every command names them
// (--motion, --markers, --subject, --out, --report, ...). Declared once; a command lists
// the ones it reads (apps/command.h SharedOptions) and may give one its own help text
// (OptionGroup::WithDefault), its usage says what the file is to it. Python takes these
// as arguments (paths or the objects other functions return), not as keywords.
#ifndef MOCAPSOLVE_SETTINGS_FILE_SETTINGS_H_
#define MOCAPSOLVE_SETTINGS_FILE_SETTINGS_H_

#include <string>

#include "settings/option.h"

namespace mocapsolve {

struct FileSettings {
  std::string motion;     // .bvh, .glb/.gltf, .fbx, or .amc with skeleton.
  std::string skeleton;   // The .asf of an .amc; a skeleton file.
  std::string markers;    // .c3d or .trc.
  std::string markerset;  // .json: each marker's joint and offset.
  std::string subject;    // .json: skeleton, marker set, axes and units in one.
  std::string character;  // .glb/.gltf characters, comma-separated.
  std::string target;     // A target character (.glb/.gltf/.fbx).
  std::string out;        // The output (its extension picks the format).
  std::string report;     // What the command measured, as JSON.
  std::string config;     // JSON of options (pipeline --config).
  // One command's inputs: retarget's and joint_map's source, blend's two motions, batch's
  // manifest and marker-file pattern, fit_skeleton's template, propagate's edit, view's
  // overlays.
  std::string source, a, b, manifest, markers_glob, template_subject, edit, repair_report, falloff, compare;
  // One command's outputs besides --out.
  std::string out_dir, out_markers, out_motion, out_subject, out_markerset, write_markerset, out_bvh, mask_out,
      table_csv, residuals_csv, weights_csv, write_manifest, demo_out;
};

const OptionGroup<FileSettings>& FileSettingOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SETTINGS_FILE_SETTINGS_H_
