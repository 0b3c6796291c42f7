#include "settings/file_read_settings.h"

namespace mocapsolve {

const OptionGroup<FileReadSettings>& FileReadSettingOptions() {
  using S = FileReadSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::amc_fps, "amc_fps", "Hz", "Frame rate of AMC files, which do not store it (CMU: 120).")
      .Add(&S::animation, "animation",
           "Animation of a .glb/.gltf/.fbx motion file: name or index (default: the first).")
      .Add(&S::sample_fps, "sample_fps", "Hz",
           "Sampling rate of .glb/.gltf/.fbx animations; 0 = the key rate when the keys are uniformly spaced, "
           "else 30.")
      .Add(&S::skeleton_units, "skeleton_units",
           "Unit of a skeleton whose file does not state one (BVH): mm, cm, m or in; needed to relate it to "
           "marker files and mm-based weights.")
      .Add(&S::axes, "axes",
           "Marker file axes to skeleton axes: 'y,z,x' means (x, y, z)_skeleton = (y, z, x)_file; CMU C3D "
           "(Z-up) onto CMU ASF/AMC (Y-up) is y,z,x.")
      .Add(&S::marker_scale, "marker_scale", "",
           "Marker file units to skeleton units; 0 = from the files' declared units (C3D POINT:UNITS, TRC "
           "Units, ASF :units).")
      .Add(&S::include_model_outputs, "include_model_outputs",
           "C3D: read model outputs (POINT:ANGLES/FORCES/MOMENTS/POWERS/REACTIONS/SCALARS, Plug-in Gait "
           "virtual points such as PELO, CentreOfMass) as markers; by default they are left out of the markers "
           "and kept unchanged when the file is rewritten.")
      .Add(&S::subject_prefix, "subject_prefix",
           "C3D or TRC with several subjects (SUBJECTS:LABEL_PREFIXES, 'Name:LASI' labels): read this subject's points "
           "(name, 'Name:' or a SUBJECTS:NAMES entry), its prefix stripped; the other subjects' points are "
           "ignored. Without it such a file is read as the subject file's own subject (its label prefix) when the "
           "file has it, else as the subject with the most points (an actor, not a prop), and a warning lists "
           "the others.")
      .Add(&S::ignore_markers, "ignore_markers",
           "Marker labels (comma-separated, as the file spells them, or without a subject's 'Name:' prefix) read "
           "as missing in "
           "every frame: a marker that came off or was mislabelled through the take, which the quality gate's "
           "advice names; the repair fills it from the solved motion like any gap.");
  return *group;
}

MotionFileOptions MotionReadOptionsOf(const FileReadSettings& settings, const std::string& skeleton_path) {
  MotionFileOptions options;
  options.skeleton_path = skeleton_path;
  options.amc_frame_rate = settings.amc_fps;
  options.animation = settings.animation;
  options.sample_rate = settings.sample_fps;
  options.skeleton_units = settings.skeleton_units;
  return options;
}

MarkerReadOptions MarkerReadOptionsOf(const FileReadSettings& settings) {
  MarkerReadOptions options;
  options.include_model_outputs = settings.include_model_outputs;
  options.subject_prefix = settings.subject_prefix;
  options.ignore_markers = settings.ignore_markers;
  return options;
}

}  // namespace mocapsolve
