#include "tasks/propagate_task.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "settings/method_settings.h"
#include "io/comma_list.h"
#include "io/motion_file.h"
#include "pipeline/memory_estimate.h"
#include "problems/edit_propagation/foot_contacts.h"
#include "problems/edit_propagation/pose_edit.h"
#include "tasks/console_text.h"

namespace mocapsolve {
namespace {

double Correlation(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd x = a.array() - a.mean(), y = b.array() - b.mean();
  const double denominator = std::sqrt(x.squaredNorm() * y.squaredNorm());
  return denominator > 0.0 ? x.dot(y) / denominator : 0.0;
}

// The edits of an edit file, each checked against the clip (and a given --frame).
Status EditsFromFile(const Skeleton& skeleton, const Motion& motion, const PropagateConfig& config,
                     std::vector<PoseEdit>* edits, JsonObject* report) {
  std::vector<EditFileEntry> entries;
  Status status = ReadPoseEdits(config.edit, skeleton, motion, edits, &entries);
  if (!status.ok()) return status;
  if (config.frame >= 0 && (entries.size() != 1 || entries[0].frame != config.frame)) {
    return Status::Error(entries[0].where + ": frame: the file edits frame " + std::to_string(entries[0].frame) +
                         (entries.size() > 1 ? " and others" : "") + ", but --frame=" + std::to_string(config.frame));
  }
  report->Add("source", config.edit);
  return Status::Ok();
}

// The IK edit: the pose of `frame` solved so that the joints reach their targets.
Status EditFromIk(const Skeleton& skeleton, const Motion& motion, const PropagateConfig& config,
                  std::vector<PoseEdit>* edits, PropagateResult* result, JsonObject* report) {
  if (config.frame < 0 || config.frame >= motion.num_frames()) {
    return Status::Error("--frame: expected 0 <= frame < " + std::to_string(motion.num_frames()) +
                         " with --ik_target, got " + std::to_string(config.frame));
  }
  std::vector<IkTarget> targets;
  Status status = ParseIkTargets(config.ik_target, skeleton, &targets);
  if (!status.ok()) return status;
  MarkerSolveOptions solve;
  status = MarkerSolveOptionsFromSettings(config.solver, skeleton.unit(), &solve);
  if (!status.ok()) return status;
  solve.prior_translation_weight = config.propagate.ik_root_weight;
  PoseEdit edit;
  IkEditReport& ik = result->ik_report;
  status = SolveIkEdit(skeleton, motion, config.frame, targets, solve, &edit, &ik);
  if (!status.ok()) return status;
  edits->push_back(std::move(edit));
  result->ik = true;
  report->Add("source", "ik_target").Add("ik_target", config.ik_target).Add("solver", config.solver.solver)
      .Add("ik_iterations", ik.solve.iterations).Add("ik_max_target_error", ik.max_target_error)
      .Add("ik_final_cost", ik.solve.final_cost);
  return Status::Ok();
}

// Foot contacts of the source: drift measured always, held with keep_contacts.
Status Contacts(const Skeleton& skeleton, const Motion& motion, const PropagateConfig& config,
                const std::function<void(int, int)>& progress, PropagateResult* result, JsonObject* report) {
  const PropagateSettings& s = config.propagate;
  result->unit_assumed = !skeleton.unit().known();
  const double units_per_cm = result->unit_assumed ? 1.0 : 0.01 / skeleton.unit().metres_per_unit;
  FootContactOptions contact_options;
  contact_options.height_threshold = s.contact_height_cm * units_per_cm;
  contact_options.speed_threshold = s.contact_speed_cm * units_per_cm;
  for (const std::string& name : SplitFields(config.foot_joints, ',')) {
    if (name.empty()) continue;
    const int joint = skeleton.FindJoint(name);
    if (joint < 0) return Status::Error("--foot_joints: unknown joint '" + name + "'");
    contact_options.joints.push_back(joint);
  }
  FootContacts contacts;
  const Status found = DetectFootContacts(skeleton, motion, contact_options, &contacts);
  if (s.keep_contacts && !found.ok()) return Status::Error("--keep_contacts: " + found.message());
  if (!found.ok()) return Status::Ok();
  result->contacts_found = true;
  result->contact_frames = contacts.ContactFrames();
  result->drift_cm_before = MaxContactDrift(skeleton, contacts, result->propagated) / units_per_cm;
  report->Add("contact_frames", contacts.ContactFrames()).Add("contact_samples", contacts.ContactSamples())
      .Add("max_drift_cm_without_keep", result->drift_cm_before);
  if (!s.keep_contacts) return Status::Ok();
  ContactSolveOptions solve;
  solve.prior_weight = s.contact_prior_cm * units_per_cm;
  solve.blend_seconds = s.contact_blend_s;
  ContactSolveReport kept;
  const int total = result->propagated.num_frames();
  Status status = KeepContacts(skeleton, contacts, solve, &result->propagated, &kept, [&](int done) {
    if (progress) progress(done, total);
  });
  if (!status.ok()) return Status::Error("--keep_contacts: " + status.message());
  result->drift_cm_after = kept.max_drift_after / units_per_cm;
  report->Add("max_drift_cm_with_keep", result->drift_cm_after).Add("frames_resolved", kept.frames_solved)
      .Add("failed_frames", kept.failed_frames).Add("contact_solve_seconds", kept.solve_seconds);
  return Status::Ok();
}

}  // namespace

Status RunPropagate(const Skeleton& skeleton, const Motion& motion, const PropagateConfig& config,
                    const std::function<void(int done, int total)>& contact_progress, PropagateResult* result) {
  *result = PropagateResult();
  if (config.edit.empty() == config.ik_target.empty()) {
    return Status::Error("give exactly one of --edit=EDIT.json and --ik_target=JOINT:x,y,z");
  }
  if (config.frame < -1) {  // -1 = not given.
    return Status::Error("--frame: expected a frame index >= 0, got " + std::to_string(config.frame));
  }
  const std::string& method = config.method;
  Status status = PropagateMethodOption().Validate(MethodSetting{method});
  if (!status.ok()) return status;
  status = PropagateSettingOptions().Validate(config.propagate);
  if (!status.ok()) return status;
  if (motion.num_frames() == 0) return Status::Error("the motion has no frames");
  if (method == "green" || config.propagate.compare_falloffs) {  // The Green's function over every frame.
    status = CheckMemoryLimit(GreenFunctionMemory(motion.num_frames()), config.memory.memory_mb, "the motion");
    if (!status.ok()) return status;
  }
  FalloffOptions falloff;
  status = FalloffOptionsFromSettings(config.falloff, motion.num_frames(), &falloff);
  if (!status.ok()) return status;
  result->region_begin = falloff.region_begin;
  result->region_end = falloff.region_end < 0 ? motion.num_frames() : falloff.region_end;

  std::vector<PoseEdit> edits;
  JsonObject edit_report;
  status = config.edit.empty() ? EditFromIk(skeleton, motion, config, &edits, result, &edit_report)
                               : EditsFromFile(skeleton, motion, config, &edits, &edit_report);
  if (!status.ok()) return status;
  for (const PoseEdit& edit : edits) {
    if (edit.frame < result->region_begin || edit.frame >= result->region_end) {
      return Status::Error("--region: edited frame " + std::to_string(edit.frame) + " lies outside " +
                           std::to_string(result->region_begin) + ":" + std::to_string(result->region_end));
    }
    result->frames.push_back(edit.frame);
  }

  // Falloff weights, one field per edit.
  EditWeightSettings weight_settings;
  weight_settings.harmonic_ground = config.propagate.harmonic_ground;
  weight_settings.spline_width = config.propagate.spline_width;
  weight_settings.sparse_library = config.solver.sparse_library;
  status = ComputeEditWeights(method, skeleton, motion, falloff, result->frames, weight_settings, &result->weights);
  if (!status.ok()) return status;
  JsonObject comparison;
  if (config.propagate.compare_falloffs) {
    for (const char* other : {"green", "harmonic", "spline"}) {
      if (other == method) continue;
      EditWeights alternative;
      status = ComputeEditWeights(other, skeleton, motion, falloff, result->frames, weight_settings, &alternative);
      if (!status.ok()) return status;
      const Eigen::VectorXd& a = result->weights.weights[0];
      const Eigen::VectorXd& b = alternative.weights[0];
      const FalloffComparison c{other, Correlation(a, b), (a - b).cwiseAbs().maxCoeff()};
      result->comparisons.push_back(c);
      comparison.Add(other, JsonObject().Add("correlation", c.correlation).Add("max_difference", c.max_difference));
    }
  }
  status = PropagateEdits(skeleton, motion, edits, result->weights.weights, &result->propagated);
  if (!status.ok()) return status;
  JsonObject contact_report;
  status = Contacts(skeleton, motion, config, contact_progress, result, &contact_report);
  if (!status.ok()) return status;

  const std::vector<JsonValue> frame_values(result->frames.begin(), result->frames.end());
  result->report.Add("method", method).Add("frames", frame_values).Add("region_begin", result->region_begin)
      .Add("region_end", result->region_end).Add("edit", edit_report).Add("falloff", result->weights.report)
      .Add("contacts", contact_report).Add("units_assumed_cm", result->unit_assumed);
  if (config.propagate.compare_falloffs) result->report.Add("comparison", comparison);
  return Status::Ok();
}

std::string PropagateSummary(const PropagateConfig& config, const PropagateResult& result) {
  std::string text;
  if (result.ik) {
    AppendF(&text, "IK edit at frame %d (%s): %d iterations, max target error %.4g skeleton units\n", config.frame,
            config.solver.solver.c_str(), result.ik_report.solve.iterations, result.ik_report.max_target_error);
  }
  for (const FalloffComparison& c : result.comparisons) {
    AppendF(&text, "%s vs %s falloff of frame %d: correlation %.4f, max |difference| %.4f\n", config.method.c_str(),
            c.method.c_str(), result.frames[0], c.correlation, c.max_difference);
  }
  if (!result.contacts_found) return text;
  const char* assumed = result.unit_assumed ? " (skeleton unit unknown: assumed cm)" : "";
  if (config.propagate.keep_contacts) {
    AppendF(&text, "contacts: %d frames, max foot drift %.3f cm before the re-solve, %.3f cm after%s\n",
            result.contact_frames, result.drift_cm_before, result.drift_cm_after, assumed);
  } else {
    AppendF(&text, "contacts: %d frames, max foot drift %.3f cm (use --keep_contacts to hold them)%s\n",
            result.contact_frames, result.drift_cm_before, assumed);
  }
  return text;
}

std::string FalloffWeightsCsv(const PropagateResult& result) {
  const std::vector<Eigen::VectorXd>& weights = result.weights.weights;
  std::ostringstream csv;
  csv.precision(9);
  csv << "frame";
  if (weights.size() == 1) {
    csv << ",weight";
  } else {
    for (int frame : result.frames) csv << ",weight_" << frame;
  }
  csv << "\n";
  for (int f = 0; f < (weights.empty() ? 0 : weights[0].size()); ++f) {
    csv << f;
    for (const Eigen::VectorXd& w : weights) csv << "," << w[f];
    csv << "\n";
  }
  return csv.str();
}

Status MakePropagateViewScene(const std::string& motion_name, const Skeleton& skeleton, const Motion& motion,
                              const PropagateResult& result, ViewScene* scene) {
  ViewTransform transform;
  Status made = MakeMotionViewTransform(motion_name, skeleton, motion, -1, &transform);
  if (!made.ok()) return made;
  scene->title = "propagate: " + FileStem(motion_name);
  scene->frame_rate = motion.frame_rate > 0 ? motion.frame_rate : 30.0;
  scene->notes.push_back(transform.note);
  scene->skeletons.push_back(MakeViewSkeleton("propagated", skeleton, result.propagated, transform));
  ViewSkeleton original = MakeViewSkeleton("original", skeleton, motion, transform);
  original.ghost = true;
  scene->skeletons.push_back(std::move(original));
  for (size_t e = 0; e < result.weights.weights.size(); ++e) {
    const Eigen::VectorXd& weights = result.weights.weights[e];
    ViewCurve curve;
    curve.name = "falloff (edit at " + std::to_string(result.frames[e]) + ")";
    for (int f = 0; f < weights.size(); ++f) curve.values.push_back(static_cast<float>(weights[f]));
    scene->curves.push_back(std::move(curve));
  }
  return Status::Ok();
}

}  // namespace mocapsolve
