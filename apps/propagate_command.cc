// mocapsolve propagate --motion=IN.bvh --frame=I --edit=EDIT.json|--ik_target=JOINT:x,y,z
// [--method=green|harmonic|spline] [--keep_contacts] --out=OUT.bvh: an edit at one or more
// frames propagated through a clip (Dean, Lewis & Chalmers 2018, eqs. 4-5), with the
// Green's-function, harmonic or spline falloff, optionally keeping planted feet in place.
// problems/edit_propagation/.
//
// Flags: --frame is distance's (apps/distance_command.cc); the falloff flags (--sigma, --sigma_scale, --eigenpairs, --region, --knn, ...)
// are defined once in apps/falloff_flags.cc and shared with `distance`; --method is
// blend's flag (apps/blend_command.cc), read here with its own default (green) when not
// given; --solver/--prior_weight and the other solver knobs come from apps/solver_flags.cc.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/falloff_flags.h"
#include "apps/progress.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/comma_list.h"
#include "io/edit_file.h"
#include "io/motion_file.h"
#include "pipeline/edit_weights.h"
#include "problems/edit_propagation/falloff.h"
#include "problems/edit_propagation/foot_contacts.h"
#include "problems/edit_propagation/ik_edit.h"
#include "problems/edit_propagation/pose_edit.h"

DECLARE_string(method);  // apps/blend_command.cc; here green | harmonic | spline.
DECLARE_string(sparse_library);  // apps/solver_flags.cc: eigen_sparse | suite_sparse.

// apps/distance_command.cc; here required with --ik_target, optional with --edit (then it
// must match a one-edit file's "frame").
DECLARE_int32(frame);
DEFINE_string(edit, "", "Edit file (.json, io/edit_file.h): rotation offsets per joint and a "
              "root translation offset at one or several frames.");
DEFINE_string(ik_target, "", "IK edit: JOINT:x,y,z moves JOINT to (x, y, z) (world, skeleton "
              "units) at --frame; several targets separated by ';'.");
DEFINE_double(ik_root_weight, 1.0, "IK edit: pull of the root translation toward the original, "
              "per skeleton unit (0 lets the root slide freely).");
DEFINE_double(harmonic_ground, mocapsolve::EditWeightSettings().harmonic_ground, "--method=harmonic: weight of every frame's edge to a "
              "ground node held at 0, as a fraction of the graph's mean degree, so the field "
              "decays away from the edit. On 16_15 (arm edits at frames 30-400, default --knn) 0.002 "
              "follows the Green's falloff with correlation 0.90-0.94. 0 = pure harmonic, with the "
              "clip's ends held at 0 instead (correlation 0.24-0.96: often nearly flat).");
DEFINE_double(spline_width, mocapsolve::EditWeightSettings().spline_width, "--method=spline: half-width of the cubic bump, frames.");
DEFINE_bool(keep_contacts, false, "Re-solve frames where a foot was planted in the source so "
            "that it stays where it was (legs absorb the edit; the root keeps it).");
DEFINE_string(foot_joints, "", "Comma-separated foot joints for contacts (default: names with "
              "foot, toe or ankle).");
DEFINE_double(contact_height_cm, 5.0, "Contact: foot joint at most this high above its lowest "
              "point in the clip (cm).");
DEFINE_double(contact_speed_cm, 20.0, "Contact: foot joint slower than this (cm/s).");
DEFINE_double(contact_prior_cm, 1.0, "Contact re-solve: cm of foot error worth one radian of "
              "change from the propagated pose (smaller: feet held tighter).");
DEFINE_double(contact_blend_s, 0.2, "Contact re-solve: seconds over which each leg correction "
              "eases in and out around planted frames (0 = off: legs pop).");
DEFINE_string(weights_csv, "", "Write the falloff weights: frame,weight (one column per edit).");
DEFINE_bool(compare_falloffs, false, "Also compute the other falloffs of the first edit and "
            "report their correlation and largest difference with the chosen one.");

namespace mocapsolve {

namespace {

// Skeleton units per cm; *assumed when the skeleton's unit is unknown (then cm).
double UnitsPerCm(const Skeleton& skeleton, bool* assumed) {
  *assumed = !skeleton.unit().known();
  return *assumed ? 1.0 : 0.01 / skeleton.unit().metres_per_unit;
}

double Correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd x = a.array() - a.mean(), y = b.array() - b.mean();
  const double denominator = std::sqrt(x.squaredNorm() * y.squaredNorm());
  return denominator > 0.0 ? x.dot(y) / denominator : 0.0;
}

EditWeightSettings EditWeightSettingsFromFlags() {
  EditWeightSettings settings;
  settings.harmonic_ground = FLAGS_harmonic_ground;
  settings.spline_width = FLAGS_spline_width;
  settings.sparse_library = SolverSettingsFromFlags().sparse_library;
  return settings;
}

Status WriteWeightsCsv(const std::string& path, const std::vector<int>& frames,
                       const std::vector<Eigen::VectorXd>& weights) {
  std::ostringstream csv;
  csv.precision(9);
  csv << "frame";
  if (weights.size() == 1) {
    csv << ",weight";
  } else {
    for (int frame : frames) csv << ",weight_" << frame;
  }
  csv << "\n";
  for (int f = 0; f < (weights.empty() ? 0 : weights[0].size()); ++f) {
    csv << f;
    for (const Eigen::VectorXd& w : weights) csv << "," << w[f];
    csv << "\n";
  }
  return WriteFileAtomically(path, csv.str());
}

Status RunPropagate(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (FLAGS_motion.empty() || FLAGS_out.empty()) return Status::Error("--motion and --out are required");
  if (FLAGS_edit.empty() == FLAGS_ik_target.empty()) {
    return Status::Error("give exactly one of --edit=EDIT.json and --ik_target=JOINT:x,y,z");
  }
  if (FLAGS_frame < -1) {  // -1 = not given.
    return Status::Error("--frame: expected a frame index >= 0, got " + std::to_string(FLAGS_frame));
  }
  if (!IsTextOutputPath(FLAGS_out, ".bvh")) return Status::Error(FLAGS_out + ": expected a .bvh");
  Status status = CheckNotAnInput(FLAGS_out, FLAGS_motion);
  if (status.ok() && !FLAGS_edit.empty()) status = CheckNotAnInput(FLAGS_out, FLAGS_edit);
  if (status.ok()) status = CheckViewFlag({FLAGS_motion, FLAGS_edit});
  if (!status.ok()) return status;
  const std::string method = FLAGS_method;
  if (method != "green" && method != "harmonic" && method != "spline") {
    return Status::Error("--method: expected green, harmonic or spline, got '" + method + "'");
  }

  Skeleton skeleton;
  Motion motion;
  SetStage("inputs");
  status = LoadMotion(FLAGS_motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(FLAGS_motion, motion);
  if (!status.ok()) return status;
  const int num_frames = motion.num_frames();
  FalloffOptions falloff;
  status = FalloffOptionsFromFlags(num_frames, &falloff);
  if (!status.ok()) return status;
  const int region_begin = falloff.region_begin;
  const int region_end = falloff.region_end < 0 ? num_frames : falloff.region_end;

  // The edits.
  std::vector<PoseEdit> edits;
  JsonObject edit_report;
  if (!FLAGS_edit.empty()) {
    std::vector<EditFileEntry> entries;
    status = ReadEditFile(FLAGS_edit, skeleton, &entries);
    if (!status.ok()) return status;
    if (FLAGS_frame >= 0 && (entries.size() != 1 || entries[0].frame != FLAGS_frame)) {
      return Status::Error(entries[0].where + ": frame: the file edits frame " +
                           std::to_string(entries[0].frame) + (entries.size() > 1 ? " and others" : "") +
                           ", but --frame=" + std::to_string(FLAGS_frame));
    }
    for (const EditFileEntry& entry : entries) {
      if (entry.frame >= num_frames) {
        return Status::Error(entry.where + ": frame: " + std::to_string(entry.frame) +
                             " is past the motion's last frame " + std::to_string(num_frames - 1));
      }
      PoseOffsets offsets;
      offsets.frame = entry.frame;
      offsets.rotation_offsets = entry.rotation_offsets_rad;
      offsets.root_translation_offset = entry.root_translation_offset;
      PoseEdit edit;
      status = MakeEdit(motion, offsets, &edit);
      if (!status.ok()) return Status::Error(entry.where + ": " + status.message());
      edits.push_back(std::move(edit));
    }
    edit_report.Add("source", FLAGS_edit);
  } else {
    if (FLAGS_frame < 0 || FLAGS_frame >= num_frames) {
      return Status::Error("--frame: expected 0 <= frame < " + std::to_string(num_frames) +
                           " with --ik_target, got " + std::to_string(FLAGS_frame));
    }
    std::vector<IkTarget> targets;
    status = ParseIkTargets(FLAGS_ik_target, skeleton, &targets);
    if (!status.ok()) return status;
    MarkerSolveOptions solve;
    status = MarkerSolveOptionsFromFlags(skeleton.unit(), &solve);
    if (!status.ok()) return status;
    if (!(FLAGS_ik_root_weight >= 0.0)) return Status::Error("--ik_root_weight must be >= 0");
    solve.prior_translation_weight = FLAGS_ik_root_weight;
    PoseEdit edit;
    IkEditReport ik;
    status = SolveIkEdit(skeleton, motion, FLAGS_frame, targets, solve, &edit, &ik);
    if (!status.ok()) return status;
    edits.push_back(std::move(edit));
    std::printf("IK edit at frame %d (%s): %d iterations, max target error %.4g skeleton units\n",
                FLAGS_frame, SolverSettingsFromFlags().solver.c_str(), ik.solve.iterations, ik.max_target_error);
    edit_report.Add("source", "ik_target").Add("ik_target", FLAGS_ik_target)
        .Add("solver", SolverSettingsFromFlags().solver).Add("ik_iterations", ik.solve.iterations)
        .Add("ik_max_target_error", ik.max_target_error).Add("ik_final_cost", ik.solve.final_cost);
  }
  std::vector<int> frames;
  for (const PoseEdit& edit : edits) {
    if (edit.frame < region_begin || edit.frame >= region_end) {
      return Status::Error("--region: edited frame " + std::to_string(edit.frame) + " lies outside " +
                           std::to_string(region_begin) + ":" + std::to_string(region_end));
    }
    frames.push_back(edit.frame);
  }

  // Falloff weights, one field per edit.
  const EditWeightSettings weight_settings = EditWeightSettingsFromFlags();
  EditWeights chosen;
  SetStage("falloff");
  status = ComputeEditWeights(method, skeleton, motion, falloff, frames, weight_settings, &chosen);
  if (!status.ok()) return status;
  JsonObject comparison;
  if (FLAGS_compare_falloffs) {
    for (const char* other : {"green", "harmonic", "spline"}) {
      if (other == method) continue;
      EditWeights alternative;
      status = ComputeEditWeights(other, skeleton, motion, falloff, frames, weight_settings, &alternative);
      if (!status.ok()) return status;
      const Eigen::VectorXd& a = chosen.weights[0];
      const Eigen::VectorXd& b = alternative.weights[0];
      const double correlation = Correlation(a, b);
      const double max_difference = (a - b).cwiseAbs().maxCoeff();
      std::printf("%s vs %s falloff of frame %d: correlation %.4f, max |difference| %.4f\n",
                  method.c_str(), other, frames[0], correlation, max_difference);
      comparison.Add(other, JsonObject().Add("correlation", correlation).Add("max_difference", max_difference));
    }
  }

  Motion propagated;
  SetStage("propagate");
  status = PropagateEdits(skeleton, motion, edits, chosen.weights, &propagated);
  if (!status.ok()) return status;

  // Foot contacts of the source: drift measured always, fixed with --keep_contacts.
  bool unit_assumed = false;
  const double units_per_cm = UnitsPerCm(skeleton, &unit_assumed);
  JsonObject contact_report;
  FootContactOptions contact_options;
  contact_options.height_threshold = FLAGS_contact_height_cm * units_per_cm;
  contact_options.speed_threshold = FLAGS_contact_speed_cm * units_per_cm;
  if (!FLAGS_foot_joints.empty()) {
    for (const std::string& name : SplitFields(FLAGS_foot_joints, ',')) {
      const int joint = skeleton.FindJoint(name);
      if (joint < 0) return Status::Error("--foot_joints: unknown joint '" + name + "'");
      contact_options.joints.push_back(joint);
    }
  }
  FootContacts contacts;
  Status contact_status = DetectFootContacts(skeleton, motion, contact_options, &contacts);
  if (FLAGS_keep_contacts && !contact_status.ok()) {
    return Status::Error("--keep_contacts: " + contact_status.message());
  }
  if (contact_status.ok()) {
    const double drift_cm = MaxContactDrift(skeleton, contacts, propagated) / units_per_cm;
    contact_report.Add("contact_frames", contacts.ContactFrames())
        .Add("contact_samples", contacts.ContactSamples())
        .Add("max_drift_cm_without_keep", drift_cm);
    if (FLAGS_keep_contacts) {
      ContactSolveOptions solve;
      if (!(FLAGS_contact_prior_cm >= 0.0)) return Status::Error("--contact_prior_cm must be >= 0");
      solve.prior_weight = FLAGS_contact_prior_cm * units_per_cm;
      solve.blend_seconds = FLAGS_contact_blend_s;
      ContactSolveReport kept;
      Progress progress("propagate: contact re-solve", propagated.num_frames(), FLAGS_quiet);
      status = KeepContacts(skeleton, contacts, solve, &propagated, &kept,
                            [&progress](int frames_done) { progress.Update(frames_done); });
      if (!status.ok()) return Status::Error("--keep_contacts: " + status.message());
      contact_report.Add("max_drift_cm_with_keep", kept.max_drift_after / units_per_cm)
          .Add("frames_resolved", kept.frames_solved).Add("failed_frames", kept.failed_frames)
          .Add("contact_solve_seconds", kept.solve_seconds);
      std::printf("contacts: %d frames, max foot drift %.3f cm before the re-solve, %.3f cm after%s\n",
                  contacts.ContactFrames(), drift_cm, kept.max_drift_after / units_per_cm,
                  unit_assumed ? " (skeleton unit unknown: assumed cm)" : "");
    } else {
      std::printf("contacts: %d frames, max foot drift %.3f cm (use --keep_contacts to hold them)%s\n",
                  contacts.ContactFrames(), drift_cm,
                  unit_assumed ? " (skeleton unit unknown: assumed cm)" : "");
    }
  }

  status = WriteBvh(FLAGS_out, skeleton, propagated);
  if (!status.ok()) return status;
  if (!FLAGS_weights_csv.empty()) {
    status = WriteWeightsCsv(FLAGS_weights_csv, frames, chosen.weights);
    if (!status.ok()) return status;
  }
  // --view: the propagated clip over the original (ghosted), and each edit's falloff.
  status = WriteViewFlag([&](ViewScene* scene) {
    ViewTransform transform;
    Status made = MakeMotionViewTransform(FLAGS_motion, skeleton, motion, -1, &transform);
    if (!made.ok()) return made;
    scene->title = "propagate: " + FileStem(FLAGS_motion);
    scene->frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
    scene->notes.push_back(transform.note);
    scene->skeletons.push_back(MakeViewSkeleton("propagated", skeleton, propagated, transform));
    ViewSkeleton original = MakeViewSkeleton("original", skeleton, motion, transform);
    original.ghost = true;
    scene->skeletons.push_back(std::move(original));
    for (size_t e = 0; e < chosen.weights.size(); ++e) {
      ViewCurve curve;
      curve.name = "falloff (edit at " + std::to_string(frames[e]) + ")";
      for (int f = 0; f < chosen.weights[e].size(); ++f) curve.values.push_back(static_cast<float>(chosen.weights[e][f]));
      scene->curves.push_back(std::move(curve));
    }
    return Status::Ok();
  });
  if (!status.ok()) return status;
  std::printf("wrote %s: %d frames, %zu edit(s) at frame %d%s, %s falloff over %d:%d\n",
              FLAGS_out.c_str(), num_frames, edits.size(), frames[0], edits.size() > 1 ? " ..." : "",
              method.c_str(), region_begin, region_end);
  JsonObject report;
  std::vector<JsonValue> frame_values(frames.begin(), frames.end());
  report.Add("motion", FLAGS_motion).Add("out", FLAGS_out).Add("method", method)
      .Add("frames", frame_values).Add("region_begin", region_begin).Add("region_end", region_end)
      .Add("edit", edit_report).Add("falloff", chosen.report).Add("contacts", contact_report)
      .Add("units_assumed_cm", unit_assumed);
  if (FLAGS_compare_falloffs) report.Add("comparison", comparison);
  return WriteReport(report);
}

}  // namespace

extern const Command kPropagateCommand = {
    "propagate", "propagate a pose edit through a clip (Green's function, harmonic or spline falloff)",
    "mocapsolve propagate --motion=IN.bvh --frame=I --edit=EDIT.json|--ik_target=JOINT:x,y,z\n"
    "    [--method=green|harmonic|spline] [--sigma=S] [--region=a:b] [--keep_contacts]\n"
    "    --out=OUT.bvh [--weights_csv=w.csv] [--report=r.json] [--view=PAGE.html]\n\n"
    "Applies the edit of frame I (an edit file's rotation offsets and root translation offset,\n"
    "or an IK solve moving a joint to a point) to every frame f of the region as\n"
    "p'_f = exp(log p_f + w(f) delta) per joint (Dean, Lewis & Chalmers 2018, eqs. 4-5), with\n"
    "w the falloff: green (row of the pose-space Green's function, normalized), harmonic (the\n"
    "harmonic function on the kNN pose graph, 1 at the edit, 0 at other edits and at a ground\n"
    "node (--harmonic_ground) and at the ends of --region; Zhu et al. 2003) or spline (a cubic\n"
    "bump of half-width --spline_width frames).\n"

    "Reports the largest drift of feet planted in the source; --keep_contacts re-solves those\n"
    "frames so the feet stay put.",
    __FILE__, RunPropagate,
    "motion,out,report,method,skeleton,skeleton_units,amc_fps,animation,sample_fps,quiet,frame,view",
    // The IK edit's solve and the harmonic falloff's sparse solve.
    {SolverOptions().Only("solver,prior_weight,max_iterations,marker_weight,dls_lambda,dls_damping,sparse_library").options(),
     FalloffSettingOptions().Only("sigma,sigma_scale,eigenpairs,region,knn,falloff_kernel,feature_joints,joint_weights,"
                                  "temporal_weight").options()},
    {{"method", "green", "green | harmonic | spline: the falloff that carries the edit to the other frames."}}};

}  // namespace mocapsolve
