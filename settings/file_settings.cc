#include "settings/file_settings.h"

namespace mocapsolve {

const OptionGroup<FileSettings>& FileSettingOptions() {
  using S = FileSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::motion, "motion", "Motion file: .bvh, .glb/.gltf, .fbx, or .amc with --skeleton=X.asf.")
      .Add(&S::skeleton, "skeleton", "Skeleton file for motions that lack one: the .asf of an .amc.")
      .Add(&S::markers, "markers", "Marker file: .c3d or .trc.")
      .Add(&S::markerset, "markerset", "Marker set file (.json): which joint each marker rides on, with offsets.")
      .Add(&S::subject, "subject",
           "Subject file (.json, written by calibrate/fit_skeleton --out_subject): skeleton, marker set, axes "
           "and units in one; replaces --skeleton, --skeleton_units, --markerset, --axes and --marker_scale.")
      .Add(&S::character, "character",
           "Characters (.glb/.gltf), comma-separated. pipeline: the take is retargeted onto each and written as "
           "DIR/<name>.glb with the take as a new animation (empty: stop after the solve); view: .glb files "
           "played beside the source (--character_animation).")
      .Add(&S::target, "target",
           "Target character (.glb/.gltf): where retarget puts the motion; for convert, the character a motion "
           "is written into as a new animation (default: IN when IN is glTF; the motion's skeleton must have "
           "the character's joints).")
      .Add(&S::out, "out", "Output file (its extension picks the format).")
      .Add(&S::report, "report", "Write what the command measured to this JSON file.")
      .Add(&S::config, "config",
           "JSON file of options: keys are this command's flag names (see --print_config); flags given on the "
           "command line override it.")
      .Add(&S::source, "source",
           "Source motion: a skinned character (.glb/.gltf) or a skeleton motion (.bvh, .amc with "
           "--skeleton=X.asf, .fbx).")
      .Add(&S::a, "a", "The first motion (.bvh, or .amc with --skeleton).")
      .Add(&S::b, "b", "The second motion, same skeleton (joint names and order) as --a.")
      .Add(&S::manifest, "manifest",
           "Batch manifest (.json): {\"defaults\": {...}, \"takes\": [{\"name\", \"markers\", \"subject\", "
           "\"characters\", ...options}]}; relative paths are relative to it.")
      .Add(&S::markers_glob, "markers_glob",
           "Instead of --manifest: one take per marker file matching this pattern (quote it), all with --subject "
           "and --character.")
      .Add(&S::template_subject, "template_subject",
           "Template subject (.json): skeleton and marker set to start from (e.g. CMU subject 2 calibrated on "
           "02_01); replaces --skeleton/--markerset. --axes and --marker_scale then describe the take's marker "
           "file.")
      .Add(&S::edit, "edit",
           "Edit file (.json, io/edit_file.h): rotation offsets per joint and a root translation offset at one "
           "or several frames.")
      .Add(&S::repair_report, "repair_report",
           "A repair report (repair/pipeline --report JSON): colours the repaired samples of --markers by reason "
           "and draws the intervals on the timeline.")
      .Add(&S::falloff, "falloff", "A falloff weights CSV (propagate --weights_csv): drawn on the timeline.")
      .Add(&S::compare, "compare",
           "A second take drawn ghosted over the first: a marker file (.c3d/.trc, compared with --markers) or a "
           "motion (compared with --motion).")
      .Add(&S::out_dir, "out_dir",
           "Folder of the take's outputs (created if missing; nothing is written there when the take fails).")
      .Add(&S::out_markers, "out_markers",
           "Repaired markers (.c3d or .trc), in the input file's axes and units.")
      .Add(&S::out_motion, "out_motion", "The motion solved from the repaired markers (.bvh); optional.")
      .Add(&S::out_subject, "out_subject",
           "Also write a subject file (.json: skeleton, marker set, axes, units) that solve/repair/evaluate take "
           "as --subject.")
      .Add(&S::out_markerset, "out_markerset", "The fitted marker set (.json), in the skeleton's units.")
      .Add(&S::write_markerset, "write_markerset",
           "Also write the marker set used (e.g. the auto one) to this .json.")
      .Add(&S::out_bvh, "out_bvh", "Also write the result as BVH (target skeleton, metres).")
      .Add(&S::mask_out, "mask_out",
           "CSV of the damaged samples: frame,marker,kind (gap, fly_off, swap, noise, jitter, ghost, unlabelled).")
      .Add(&S::table_csv, "table_csv",
           "Also write the table as CSV (repair: one row per method and trial; leave_one_out: one row per "
           "marker).")
      .Add(&S::residuals_csv, "residuals_csv",
           "Write the written motion's per-frame marker residual as CSV: frame, time (s), markers observed, RMS "
           "and max residual (mm, or skeleton units when the unit is unknown).")
      .Add(&S::weights_csv, "weights_csv", "Write the falloff weights: frame,weight (one column per edit).")
      .Add(&S::write_manifest, "write_manifest",
           "Write the batch's manifest (e.g. the one --markers_glob built) to this file.")
      .Add(&S::demo_out, "demo_out", "Where to write the demo clip (.bvh).");
  return *group;
}

}  // namespace mocapsolve
