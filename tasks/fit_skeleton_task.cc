#include "tasks/fit_skeleton_task.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <utility>

#include "io/marker_file.h"
#include "io/marker_set_file.h"
#include "io/motion_file.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/quote_token.h"
#include "pipeline/shipped_templates.h"
#include "problems/marker_solve/associated_marker_set.h"
#include "problems/marker_solve/attachment_by_prediction.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/held_out_round.h"
#include "problems/marker_solve/locked_axes.h"
#include "problems/marker_solve/lone_joint_gauge.h"
#include "problems/marker_solve/marker_observations.h"
#include "problems/marker_solve/mean_pose.h"
#include "problems/marker_solve/rigid_marker_clusters.h"
#include "tasks/console_text.h"

namespace mocapsolve {
namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

JsonObject ChecksJson(const SubjectChecks& checks) {
  std::vector<JsonValue> failures(checks.failures.begin(), checks.failures.end());
  std::vector<JsonObject> markers;
  for (const MarkerDistance& d : checks.markers) {
    JsonObject o;
    o.Add("label", d.label).Add("joint", d.joint).Add("to_bone_cm", d.to_bone_cm).Add("to_joint_cm", d.to_joint_cm);
    markers.push_back(o);
  }
  JsonObject json;
  json.Add("passed", checks.ok()).Add("failures", failures).Add("rms_mm", checks.rms_mm)
      .Add("max_marker_bone_distance_cm", checks.max_bone_distance_cm)
      .Add("max_marker_joint_distance_cm", checks.max_joint_distance_cm)
      .Add("farthest_marker", checks.farthest_marker)
      .Add("torso_frames", checks.torso_frames)
      .Add("torso_error_mean_deg", checks.torso_error_mean_deg)
      .Add("torso_error_max_deg", checks.torso_error_max_deg)
      .Add("max_left_right_asymmetry", checks.max_asymmetry)
      .Add("least_symmetric_pair", checks.least_symmetric_pair)
      .Add("markers", markers);
  return json;
}

// The report's association: detected up and unit, per marker its segment, joint and
// confidence, the points left out and why.
JsonObject AssociationJson(const SkeletonFitResult& result) {
  const MarkerAssociation& a = result.association;
  std::vector<JsonObject> markers, excluded;
  for (size_t i = 0; i < a.markers.size(); ++i) {
    JsonObject o;
    o.Add("label", a.markers[i].label).Add("segment", a.markers[i].role).Add("joint", result.association_joints[i])
        .Add("confidence", a.markers[i].confidence).Add("cluster", a.markers[i].cluster);
    markers.push_back(o);
  }
  for (const auto& [label, why] : a.excluded) {
    JsonObject o;
    o.Add("label", label).Add("reason", why);
    excluded.push_back(o);
  }
  JsonObject json;
  json.Add("up", a.UpName()).Add("unit", a.unit.name).Add("unit_from_data", a.unit_from_data)
      .Add("height_m", a.height_m).Add("clusters", static_cast<int>(a.clusters.size())).Add("markers", markers)
      .Add("excluded", excluded);
  return json;
}

// Whether template_labels names a map itself (pairs or a file), not auto or none.
bool TemplateLabelsGiven(const SkeletonFitSettings& s) {
  return !s.template_labels.empty() && s.template_labels != kTemplateLabelsAuto &&
         s.template_labels != kTemplateLabelsNone;
}


using Observations = std::vector<std::vector<Eigen::Vector3d>>;

// A round that improves the best marker RMS by less than this share ends the rounds
// (it is kept).
constexpr double kMinRoundGain = 0.01;

// Progress events for the caller, stamped with the seconds since the fit started (none
// without a callback), so the steps report without knowing the clock.
class FitEvents {
 public:
  FitEvents(const SkeletonFitCallback& callback, std::chrono::steady_clock::time_point start)
      : callback_(callback), start_(start) {}
  bool wanted() const { return static_cast<bool>(callback_); }
  void Emit(SkeletonFitEvent event) const {
    if (!callback_) return;
    event.seconds = Seconds(start_);
    callback_(event);
  }

 private:
  const SkeletonFitCallback& callback_;
  std::chrono::steady_clock::time_point start_;
};

// Renames the template's markers to the take's labels by settings.template_labels (a
// shipped map that fits the take for auto), so that round 0 fits them under the take's labels.
Status ApplyTemplateLabels(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                           const MarkerTrajectories& file, const FitEvents& events, SkeletonFitResult* result,
                           MarkerSet* template_markers) {
  const Subject& templ = inputs.templ;
  *template_markers = templ.markers;
  Status status = Status::Ok();
  if (settings.template_labels == kTemplateLabelsAuto) {
    status = ChooseShippedTemplateLabels(templ.markers, file, &result->template_labels_map, &result->template_labels);
  } else if (TemplateLabelsGiven(settings)) {
    status = ReadTemplateLabels(settings.template_labels, &result->template_labels);
    const bool inline_pairs = settings.template_labels.find(':') != std::string::npos;
    result->template_labels_map = inline_pairs ? "inline" : settings.template_labels;
  }
  if (!status.ok()) return status;
  if (result->template_labels.empty()) return Status::Ok();
  status = RenameTemplateMarkers(result->template_labels, templ.skeleton, file, inputs.markers_path,
                                 template_markers);
  if (!status.ok()) return status;
  SkeletonFitEvent event;
  event.kind = SkeletonFitEvent::kTemplateLabels;
  event.text = result->template_labels_map;
  event.markers = static_cast<int>(result->template_labels.size());
  events.Emit(event);
  return Status::Ok();
}

// The template's markers the take holds: a template set may name markers this take lacks,
// and the fit uses the ones it has (at least 3); the others are reported absent.
Status PresentMarkers(const MarkerSet& template_markers, const MarkerTrajectories& file,
                      const std::string& markers_path, const FitEvents& events, SkeletonFitResult* result,
                      std::vector<MarkerSpec>* present) {
  std::string absent;
  for (int m = 0; m < template_markers.num_markers(); ++m) {
    if (file.FindMarker(template_markers.label(m)) >= 0) {
      present->push_back(template_markers.marker(m));
    } else {
      absent += (absent.empty() ? "" : ", ") + template_markers.label(m);
      result->absent.push_back(template_markers.label(m));
    }
  }
  if (present->size() < 3) {
    return Status::Error(markers_path + ": fewer than 3 of the template marker set's labels (--template_labels "
                         "maps the template's labels to the take's)");
  }
  if (!absent.empty()) {
    SkeletonFitEvent event;
    event.kind = SkeletonFitEvent::kAbsentMarkers;
    event.text = absent;
    events.Emit(event);
  }
  return Status::Ok();
}

// The skin check allows what the template itself holds: the fit keeps a template marker
// within its starting distance when that exceeds --max_skin_cm (skeleton_fit.h), and a
// calibrated template is trusted (CMU subject 2 calibrated on 02_01 holds RBAC 20.7 cm
// from upperback; clamping it to 12 cm fits cmu_02_05 at 16.4 mm instead of 4.6).
SubjectCheckOptions SkinCheckOptions(const Skeleton& skeleton, const std::vector<MarkerSpec>& present,
                                     double units_per_cm) {
  SubjectCheckOptions check_options;
  for (const MarkerSpec& spec : present) {
    for (const MarkerAttachment& a : spec.attachments) {
      const double cm = DistanceToBone(skeleton, a.joint, a.offset) / units_per_cm;
      check_options.max_marker_bone_distance_cm = std::max(check_options.max_marker_bone_distance_cm, cm + 0.1);
    }
  }
  return check_options;
}

// Whether round 0 goes by the association rather than the template's labels.
bool UseAssociation(const SkeletonFitSettings& settings, const MarkerSet& template_markers,
                    const MarkerTrajectories& file) {
  if (settings.associate == "always") return true;
  if (settings.associate != "auto" || TemplateLabelsGiven(settings)) return false;
  int shared = 0;
  for (int m = 0; m < template_markers.num_markers(); ++m) shared += file.FindMarker(template_markers.label(m)) >= 0;
  return shared < 3;
}

// `file` with only the markers in `labels` (in that order).
MarkerTrajectories KeepMarkers(const MarkerTrajectories& file, const std::vector<std::string>& labels) {
  MarkerTrajectories kept(labels, file.num_frames());
  kept.frame_rate = file.frame_rate;
  kept.unit = file.unit;
  kept.first_frame = file.first_frame;
  kept.subject_prefixes = file.subject_prefixes;
  kept.model_outputs = file.model_outputs;
  for (size_t k = 0; k < labels.size(); ++k) {
    const int m = file.FindMarker(labels[k]);
    for (int f = 0; f < file.num_frames(); ++f) {
      if (file.valid(f, m)) kept.SetSample(f, static_cast<int>(k), file.position(f, m), file.residual(f, m));
    }
  }
  return kept;
}

// Round 0's markers from the association: every associated marker on its segment's joint;
// the take cut to the markers (non-markers left out), its axes and scale as detected; and the
// joints the attach rounds may use (AttachableJoints of every associated marker) and those
// they leave out (HeldLimbJoints).
Status AssociateTake(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings, MarkerTrajectories* file,
                     SkeletonFitResult* result, Subject* mapping, AssociatedMarkerSet* set,
                     std::vector<int>* attach_joints, std::vector<bool>* held_limbs) {
  const Skeleton& skeleton = inputs.templ.skeleton;
  Status status = AssociateMarkers(*file, inputs.markers_path, MarkerAssociationOptions(), &result->association);
  if (!status.ok()) return status;
  status = MakeAssociatedMarkerSet(skeleton, result->association, settings.min_association_confidence, set);
  if (!status.ok()) return Status::Error(inputs.markers_path + ": " + status.message());
  result->associated = true;
  std::vector<std::string> labels;
  for (const AssociatedMarker& m : result->association.markers) {
    labels.push_back(m.label);
    const auto it = std::find_if(set->specs.begin(), set->specs.end(),
                                 [&](const MarkerSpec& spec) { return spec.label == m.label; });
    result->association_joints.push_back(it == set->specs.end() ? "" : set->joints[it - set->specs.begin()]);
  }
  *file = KeepMarkers(*file, labels);
  AssociatedMarkerSet every;
  MarkerSet segments;
  status = MakeAssociatedMarkerSet(skeleton, result->association, 0.0, &every);
  if (status.ok()) status = MarkerSet::Create(skeleton, every.specs, &segments);
  if (!status.ok()) return Status::Error(inputs.markers_path + ": " + status.message());
  *attach_joints = AttachableJoints(skeleton, segments);
  *held_limbs = HeldLimbJoints(skeleton, segments);
  mapping->axes = set->axes;
  if (result->association.unit_from_data) {
    file->unit = result->association.unit;
    mapping->marker_scale = result->association.unit.metres_per_unit / skeleton.unit().metres_per_unit;
  }
  return Status::Ok();
}

// A take fitted by its labels: the points the association finds surely no markers (a
// lab's model outputs written as points: far from the body, at the file's origin, rigid
// with nothing) and the template does not name are cut from the take, or the attach
// rounds would put them on the skin; and, with axes "auto", the file axes that put the
// take's up (detected as the association detects it: the feet are lowest) on the
// template's. An association that fails cuts nothing (an error only when the axes depend
// on it).
Status LabelledTakeFromData(const Skeleton& skeleton, const MarkerSet& template_markers,
                            const std::string& markers_path, MarkerTrajectories* file, std::string* axes,
                            std::vector<std::pair<std::string, std::string>>* not_markers) {
  MarkerAssociation association;
  Status status = AssociateMarkers(*file, markers_path, MarkerAssociationOptions(), &association);
  AssociatedMarkerSet set;
  if (status.ok() && *axes == kAxesFromData) status = MakeAssociatedMarkerSet(skeleton, association, 0.0, &set);
  if (!status.ok()) {
    if (*axes != kAxesFromData) return Status::Ok();
    return Status::Error(markers_path + ": the up axis from the data: " + status.message());
  }
  if (*axes == kAxesFromData) *axes = set.axes;
  std::vector<bool> named(file->num_markers(), false);
  for (int m = 0; m < template_markers.num_markers(); ++m) {
    const int k = file->FindMarker(template_markers.label(m));
    if (k >= 0) named[k] = true;
  }
  std::vector<bool> cut(file->num_markers(), false);
  for (const std::string& label : association.non_markers) {
    for (int k = 0; k < file->num_markers(); ++k) cut[k] = cut[k] || (file->label(k) == label && !named[k]);
  }
  std::vector<std::string> labels;
  for (int k = 0; k < file->num_markers(); ++k) {
    if (!cut[k]) labels.push_back(file->label(k));
  }
  for (const auto& [label, reason] : association.excluded) {
    const int k = file->FindMarker(label);
    if (k >= 0 && cut[k]) not_markers->emplace_back(label, reason);
  }
  if (static_cast<int>(labels.size()) < file->num_markers()) *file = KeepMarkers(*file, labels);
  return Status::Ok();
}

// The take as the rounds fit it.
struct FitTake {
  Subject mapping;                 // The template in the take's axes and scale, with the markers the take holds.
  MarkerTake take;                 // Its observations cut to `frames`.
  MarkerTrajectories model_frame;  // Every trajectory of the file in the skeleton's frame and units (for attach).
  int frames = 0;
  SubjectCheckOptions check_options;
  // Round 0's markers came from the association: the attach rounds re-attach them too (an
  // association is a start, not a template's trusted attachment).
  bool associated = false;
  // With the association: the joints the attach rounds may use (AttachableJoints of every
  // associated marker on its segment's joint, whatever its confidence; empty: all).
  std::vector<int> attach_joints;
  // The joints it leaves out, rigid with their parents in every round (HeldLimbJoints; empty:
  // none): their bones are their parents' skin for --max_skin_cm.
  std::vector<bool> held_limbs;
};

// Reads the take and sets it against the template: labels mapped, the template markers it
// lacks left out, samples in the skeleton's frame and units, frames thinned to --fit_max_frames.
Status LoadFitTake(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings, double units_per_cm,
                   const FitEvents& events, SkeletonFitResult* result, FitTake* fit) {
  const std::string& markers_path = inputs.markers_path;
  const Skeleton& skeleton = inputs.templ.skeleton;
  // The take, in the skeleton's frame and units (axes, marker_scale describe it).
  fit->mapping = inputs.templ;
  fit->mapping.axes = inputs.axes;
  fit->mapping.marker_scale = inputs.marker_scale;
  fit->mapping.label_prefix.clear();
  MarkerTrajectories file;
  Status status = inputs.trajectories != nullptr ? Status::Ok() : ReadMarkerFile(markers_path, &file);
  if (inputs.trajectories != nullptr) file = *inputs.trajectories;
  if (status.ok()) status = RequireMarkerData(markers_path, file);
  if (!status.ok()) return status;
  // The template's markers, those the map names under the take's labels.
  MarkerSet template_markers;
  status = ApplyTemplateLabels(inputs, settings, file, events, result, &template_markers);
  if (!status.ok()) return status;
  std::vector<MarkerSpec> present;
  AssociatedMarkerSet associated;
  if (UseAssociation(settings, template_markers, file)) {
    status = AssociateTake(inputs, settings, &file, result, &fit->mapping, &associated, &fit->attach_joints,
                           &fit->held_limbs);
    present = associated.specs;
    fit->associated = true;
  } else {
    status = PresentMarkers(template_markers, file, markers_path, events, result, &present);
    if (status.ok()) {
      status = LabelledTakeFromData(skeleton, template_markers, markers_path, &file, &fit->mapping.axes,
                                    &result->not_markers);
    }
    if (status.ok() && !result->not_markers.empty()) {
      SkeletonFitEvent event;
      event.kind = SkeletonFitEvent::kNotMarkers;
      for (const auto& [label, reason] : result->not_markers) {
        event.text += (event.text.empty() ? "" : "; ") + label + " (" + reason + ")";
      }
      events.Emit(event);
    }
  }
  if (!status.ok()) return status;
  fit->check_options = SkinCheckOptions(skeleton, present, units_per_cm);
  fit->check_options.head_labels = associated.head_labels;
  fit->check_options.pelvis_labels = associated.pelvis_labels;
  status = MarkerSet::Create(skeleton, std::move(present), &fit->mapping.markers);
  if (!status.ok()) return status;
  // --fit_max_frames N: every k-th frame of the whole take, not its first N (a take often
  // starts still: squat.c3d's elbows bend only after its first 600 frames, and a subject
  // fitted on those missed its right arm there by 100-240 mm). Evenly spaced, not chosen for pose variety: the pose
  // solve warm-starts each frame from the one before (sequence_solver.h), which a fixed
  // small stride keeps near, and a pose-variety pick would favour the stray samples (a
  // marker come off) that stand out most. At most N frames: the fit's cost is unchanged.
  result->frame_stride = FitFrameStride(settings.fit_max_frames, file.num_frames());
  if (result->frame_stride > 1) file = EveryNthFrame(file, result->frame_stride);
  status = TakeForSubject(fit->mapping, std::move(file), markers_path, &fit->take);
  if (!status.ok()) return status;
  fit->frames = static_cast<int>(fit->take.observed.size());
  result->frames = fit->frames;
  fit->model_frame = fit->take.trajectories;  // For auto attach.
  TransformMarkers(fit->take.transform, skeleton.unit(), &fit->model_frame);
  return Status::Ok();
}

// The fit options every round shares, from the settings (lengths in skeleton units).
SkeletonFitOptions BaseFitOptions(const SkeletonFitSettings& settings, double units_per_cm) {
  SkeletonFitOptions options;
  options.frame_step = settings.fit_frame_step;
  options.min_scale = settings.min_bone_scale;
  options.max_scale = settings.max_bone_scale;
  options.max_bone_distance = settings.max_skin_cm * units_per_cm;
  options.root_from_markers = true;
  return options;
}

// A round's own options: round 0 fits the template's markers (with the offset prior, and
// finding the outliers), an attach round fresh attachments; each starts from `scales`.
SkeletonFitOptions RoundOptions(SkeletonFitOptions options, const SkeletonFitSettings& settings, bool from_subject,
                                int round, double outlier_distance, const std::vector<double>& scales) {
  // Outliers are found in round 0, on the template's markers (a trusted attachment), and left
  // out of every round. A fresh attachment misses by a lot until its round fits it (squat.c3d's
  // round 1 starts at 59-104 mm): finding outliers in the attach rounds too left squat at
  // 10.8-19.8 mm instead of 7.94 (gates 200-400 mm).
  options.outlier_distance = round == 0 ? outlier_distance : 0.0;
  options.iterations = round > 0 ? settings.attach_iterations
                                 : settings.fit_iterations >= 0 ? settings.fit_iterations : (from_subject ? 15 : 6);
  // The template's offsets are a prior worth keeping; an attach round's are estimates
  // from a motion that is itself being fitted.
  options.offset_prior_weight = round == 0 ? settings.offset_prior : 0.0;
  options.initial_scales = scales;
  return options;
}

// A round's fit as kept: the best round, by marker RMS, with every marker attached.
struct RoundFit {
  int round = -1;
  double rms = 0.0;
  Skeleton skeleton;
  MarkerSet markers;
  Motion motion;
  SkeletonFitReport report;
  Observations observed;
};

// What a round hands the next: the model as fitted, its motion and scales, round 0's
// outliers, and the best round so far (re-attaching can also make a round worse).
struct RoundState {
  Skeleton fitted;
  MarkerSet fitted_markers;
  Motion motion;
  SkeletonFitReport report;
  std::vector<double> scales;
  // Round 0 is a candidate for the best when it already holds every marker the attach
  // finds (a template with the take's whole marker set: round 0 is a complete fit).
  bool round0_complete = false;
  // Round 0's outliers (frame, label): samples of the template's markers that its fit left out.
  std::vector<std::pair<int, std::string>> template_outliers;
  RoundFit best;
  // Every round that holds every marker of the take, with its held-out score: the kept
  // round is chosen among them (KeepHeldOutRound), `best` only decides where rounds start.
  std::vector<RoundFit> candidates;
  std::vector<double> held_out;
};

// Each round starts from the best so far: a worse round must not feed the next.
void StartFromBest(RoundState* state) {
  state->fitted = state->best.skeleton;
  state->fitted_markers = state->best.markers;
  state->motion = state->best.motion;
  state->scales = state->best.report.bone_scales;
}

// "PATH: attach round N: MESSAGE", the error of an attach round's calibration.
Status AttachError(const std::string& markers_path, int round, const Status& status) {
  return Status::Error(markers_path + ": attach round " + std::to_string(round) + ": " + status.message());
}

// Attaches every marker of the take to the skeleton as fitted (CalibrateMarkers); markers
// the template knows keep its joints (and their fitted offsets): they anchor the skeleton.
// The others are clamped to the skin; `reattached` lists (index in specs, index in
// fitted_markers) for those an earlier round attached.
Status AttachAllMarkers(const FitTake& fit, const RoundState& state, const CalibrationOptions& calibration, int round,
                        const std::string& markers_path, std::vector<MarkerSpec>* specs,
                        std::vector<std::pair<int, int>>* reattached, int* new_markers, CalibrationResult* out) {
  CalibrationResult& attached = *out;
  Status status = CalibrateMarkers(state.fitted, state.motion, fit.model_frame, calibration, nullptr, &attached);
  if (!status.ok()) return AttachError(markers_path, round, status);
  *new_markers = 0;
  for (int m = 0; m < attached.marker_set.num_markers(); ++m) {
    MarkerSpec spec = attached.marker_set.marker(m);
    const int known = state.fitted_markers.FindMarker(spec.label);
    if (known >= 0 && fit.mapping.markers.FindMarker(spec.label) >= 0 && !fit.associated) {
      // As fitted (not clamped again: the fit kept it within its own radius, which
      // can exceed max_skin_cm for a template marker), so the round starts where the
      // last one ended.
      spec = state.fitted_markers.marker(known);
    } else {
      if (known >= 0) {
        reattached->push_back({static_cast<int>(specs->size()), known});
      } else {
        ++*new_markers;
      }
      for (MarkerAttachment& a : spec.attachments) {
        if (calibration.max_bone_distance > 0.0) {
          a.offset = ClampToBone(state.fitted, a.joint, a.offset, calibration.max_bone_distance, fit.held_limbs);
        }
      }
    }
    specs->push_back(spec);
  }
  return Status::Ok();
}

// The RMS of `label` in a calibration's fit (+inf if it has none), to compare attachments.
double MarkerRms(const CalibrationResult& fit, const std::string& label) {
  for (const CalibratedMarker& c : fit.markers) {
    if (c.label == label) return c.rms;
  }
  return std::numeric_limits<double>::infinity();
}

// A marker attached in an earlier round keeps that attachment (as fitted) unless the new
// one fits the best round's motion better: so the round does not start worse than the
// state it comes from. (Keeping every earlier attachment starts squat.c3d's rounds where
// the last ended, but leaves JA1Gait35 at round 1's poor attachments, 107 mm; re-attaching
// every one started squat's rounds 4-38 mm worse.)
Status KeepBetterAttachments(const FitTake& fit, const RoundState& state, const CalibrationOptions& calibration,
                             int round, const std::string& markers_path,
                             const std::vector<std::pair<int, int>>& reattached, std::vector<MarkerSpec>* specs) {
  MarkerSet fresh;
  Status status = MarkerSet::Create(state.fitted, *specs, &fresh);
  if (!status.ok()) return status;
  CalibrationResult fresh_fit, kept_fit;
  status = EvaluateMarkerSet(state.fitted, state.motion, fit.model_frame, fresh, calibration, &fresh_fit);
  if (status.ok()) {
    status = EvaluateMarkerSet(state.fitted, state.motion, fit.model_frame, state.fitted_markers, calibration,
                               &kept_fit);
  }
  if (!status.ok()) return AttachError(markers_path, round, status);
  for (const auto& [index, known] : reattached) {
    const std::string& label = (*specs)[index].label;
    if (MarkerRms(kept_fit, label) <= MarkerRms(fresh_fit, label)) (*specs)[index] = state.fitted_markers.marker(known);
  }
  return Status::Ok();
}

// The rigid clusters (rigid_marker_clusters.h) of the round's markers over the fit take,
// as indices into `markers`.
std::vector<std::vector<int>> RoundClusters(const FitTake& fit, const MarkerSet& markers) {
  std::vector<int> columns, index;  // The take's column of each marker found, and its index in `markers`.
  for (int m = 0; m < markers.num_markers(); ++m) {
    const int column = fit.model_frame.FindMarker(markers.label(m));
    if (column < 0) continue;
    columns.push_back(column);
    index.push_back(m);
  }
  const Skeleton& skeleton = fit.mapping.skeleton;
  const double metres_per_unit = skeleton.unit().known() ? skeleton.unit().metres_per_unit : 0.01;
  const RigidClusterOptions options;
  std::vector<std::vector<int>> clusters =
      ClusterRigidMarkers(ComputePairwiseSpread(fit.model_frame, columns, metres_per_unit, options), options);
  for (std::vector<int>& cluster : clusters) {
    for (int& c : cluster) c = index[c];
  }
  return clusters;
}

// The offsets of `choices` (one attachment list per marker of `markers`, empty: none)
// fitted on the round's motion (CalibrateMarkers with fixed attachments; a blend's by
// least squares over all its offsets) and clamped to the skin; a marker the fit skips
// loses its choice.
Status FitChoices(const FitTake& fit, const Skeleton& skeleton, const Motion& motion,
                  const CalibrationOptions& calibration, const MarkerSet& markers,
                  std::vector<AttachmentChoice>* choices) {
  std::vector<MarkerSpec> specs;
  for (int s = 0; s < markers.num_markers(); ++s) {
    if ((*choices)[s].empty()) continue;
    specs.push_back(markers.marker(s));
    specs.back().attachments = (*choices)[s];
  }
  if (specs.empty()) return Status::Ok();
  MarkerSet to_fit;
  Status status = MarkerSet::Create(skeleton, std::move(specs), &to_fit);
  CalibrationResult refit;
  if (status.ok()) status = CalibrateMarkers(skeleton, motion, fit.model_frame, calibration, &to_fit, &refit);
  if (!status.ok()) return status;
  for (int s = 0; s < markers.num_markers(); ++s) {
    if ((*choices)[s].empty()) continue;
    const int k = refit.marker_set.FindMarker(markers.label(s));
    (*choices)[s].clear();
    if (k < 0) continue;
    (*choices)[s] = refit.marker_set.marker(k).attachments;
    for (MarkerAttachment& a : (*choices)[s]) {
      if (calibration.max_bone_distance > 0.0) {
        a.offset = ClampToBone(skeleton, a.joint, a.offset, calibration.max_bone_distance, fit.held_limbs);
      }
    }
  }
  return Status::Ok();
}

// Near ties of the round's attach between a marker's joint and its parent or child decided
// by prediction on the fit's own frames (attachment_by_prediction.h), the template's
// markers included: the take, unlike the calibration take, may move the joint. A marker
// without a near tie whose rigid cluster over the fit take mostly rides another joint has
// that joint as its alternative (RigidClusterCandidates), decided the same way.
Status ChooseByPrediction(const FitTake& fit, const RoundState& state, const CalibrationOptions& calibration,
                          const CalibrationResult& attached, MarkerSolveOptions solve, const Observations& observed,
                          MarkerSet* round_markers) {
  const std::vector<int> runner_up =
      PredictionCandidates(state.fitted, attached, AttachmentByPredictionOptions().tolerance);
  const std::vector<int> cluster_joint = RigidClusterCandidates(*round_markers, RoundClusters(fit, *round_markers));
  const int markers = round_markers->num_markers();
  std::vector<AttachmentChoice> single(markers);
  bool any = false;
  for (int s = 0; s < markers; ++s) {
    const MarkerSpec& spec = round_markers->marker(s);
    if (spec.attachments.size() != 1) continue;
    const int k = attached.marker_set.FindMarker(spec.label);
    const int j = spec.attachments[0].joint;
    int other = -1;
    if (k >= 0 && runner_up[k] >= 0) {
      const int a = attached.marker_set.marker(k).attachments[0].joint, b = runner_up[k];
      other = j == a ? b : (j == b ? a : -1);
    }
    if (other < 0) other = cluster_joint[s];
    if (other < 0) continue;
    single[s] = {{other, 1.0, Eigen::Vector3d::Zero()}};
    any = true;
  }
  if (!any) return Status::Ok();
  const Status status = FitChoices(fit, state.fitted, state.motion, calibration, *round_markers, &single);
  if (!status.ok()) return status;
  std::vector<std::vector<AttachmentChoice>> alternatives(markers);
  for (int s = 0; s < markers; ++s) {
    if (!single[s].empty()) alternatives[s].push_back(single[s]);
  }
  if (solve.rest_prior_needs_reference || !solve.rest_rotations.empty()) {
    solve.rest_rotations = MeanPose(state.fitted, state.motion);
  }
  return ChooseAmongAttachments(state.fitted, observed, alternatives, solve, {}, round_markers, nullptr);
}

// An attach round's markers (every marker of the take attached) and their observations,
// round 0's outliers left out; round 1 tells whether round 0 was already complete.
Status AttachRound(const FitTake& fit, double max_bone_distance, const MarkerSolveOptions& solve_options, int round,
                   const std::string& markers_path, RoundState* state, MarkerSet* round_markers,
                   Observations* observed) {
  CalibrationOptions calibration;
  calibration.max_bone_distance = max_bone_distance;
  calibration.candidate_joints = fit.attach_joints;
  std::vector<MarkerSpec> specs;
  std::vector<std::pair<int, int>> reattached;
  int new_markers = 0;
  CalibrationResult attached;
  Status status =
      AttachAllMarkers(fit, *state, calibration, round, markers_path, &specs, &reattached, &new_markers, &attached);
  if (!status.ok()) return status;
  if (!reattached.empty()) {
    status = KeepBetterAttachments(fit, *state, calibration, round, markers_path, reattached, &specs);
    if (!status.ok()) return status;
  }
  if (round == 1) state->round0_complete = new_markers == 0;
  status = MarkerSet::Create(state->fitted, std::move(specs), round_markers);
  if (!status.ok()) return status;
  status = GatherObservations(*round_markers, fit.take.trajectories, fit.take.transform, observed);
  if (!status.ok()) return Status::Error(markers_path + ": " + status.message());
  observed->resize(fit.frames);
  for (const auto& [f, label] : state->template_outliers) {
    const int m = round_markers->FindMarker(label);
    if (m >= 0) (*observed)[f][m].setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  status = ChooseByPrediction(fit, *state, calibration, attached, solve_options, *observed, round_markers);
  if (!status.ok()) return AttachError(markers_path, round, status);
  return Status::Ok();
}

// The round's start event; its progress, done and stop events are copies of it.
SkeletonFitEvent RoundStartEvent(int round, int rounds, int markers, int frames, int iterations) {
  SkeletonFitEvent started;
  started.kind = SkeletonFitEvent::kRoundStart;
  started.round = round;
  started.rounds = rounds;
  started.markers = markers;
  started.frames = frames;
  started.iterations = iterations;
  return started;
}

// Fits the round (FitSkeletonToMarkers, reporting its progress) and makes the fit the
// state's model; round 0's outliers are noted and left out of its observations.
Status FitRound(const FitTake& fit, const SkeletonFitOptions& options, const MarkerSolveOptions& solve_options,
                const MarkerSet& round_markers, const SkeletonFitEvent& started, const FitEvents& events,
                const std::string& markers_path, RoundState* state, Observations* observed,
                SkeletonFitResult* result) {
  const SkeletonFitProgress progress = [&](int iteration, double rms) {
    SkeletonFitEvent event = started;
    event.kind = SkeletonFitEvent::kIteration;
    event.iteration = iteration;
    event.rms = rms;
    events.Emit(event);
  };
  // Pose solves of this round: 0 before the first step (the outlier passes' too), k the one of step k.
  const std::function<void(int, int)> frame_progress = [&](int step, int frames_done) {
    SkeletonFitEvent event = started;
    event.kind = SkeletonFitEvent::kFrames;
    event.iteration = step;
    event.frames_done = frames_done;
    events.Emit(event);
  };
  Skeleton next;
  MarkerSet next_markers;
  const Status status = FitSkeletonToMarkers(state->fitted, round_markers, *observed, solve_options, options, &next,
                                             &next_markers, &state->motion, &state->report, progress,
                                             events.wanted() ? frame_progress : nullptr);
  if (!status.ok()) return Status::Error(markers_path + ": " + status.message());
  state->motion.frame_rate = fit.take.trajectories.frame_rate > 0.0 ? fit.take.trajectories.frame_rate : 120.0;
  state->fitted = std::move(next);
  state->fitted_markers = std::move(next_markers);
  state->scales = state->report.bone_scales;
  const SkeletonFitReport& report = state->report;
  if (started.round == 0) {
    for (const auto& [f, m] : report.outliers) state->template_outliers.push_back({f, round_markers.label(m)});
    for (const auto& [f, m] : report.outliers) (*observed)[f][m].setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  result->rounds.push_back({started.round, state->fitted_markers.num_markers(), report.rms,
                            static_cast<int>(state->template_outliers.size())});
  SkeletonFitEvent done = started;
  done.kind = SkeletonFitEvent::kRoundDone;
  done.markers = state->fitted_markers.num_markers();
  done.rms_first = report.rms.front();
  done.rms = report.rms.back();
  events.Emit(done);
  return Status::Ok();
}

// Keeps the round as the best when it is better (or not comparable: its markers differ
// from the best's); false when the rounds stop: it did not improve the best, or by less
// than kMinRoundGain.
bool KeepBestRound(int round, int rounds, const Observations& observed, const SkeletonFitEvent& started,
                   const FitEvents& events, RoundState* state) {
  RoundFit& best = state->best;
  const double rms = state->report.rms.back();
  const bool comparable = round >= 2 || (round == 1 && state->round0_complete);  // Same markers as the best.
  if (comparable && !(rms < best.rms)) {
    // The next round would start from the same best state and attach alike.
    SkeletonFitEvent stopped = started;
    stopped.kind = SkeletonFitEvent::kStopped;
    events.Emit(stopped);
    return false;
  }
  const bool small_gain = comparable && rms > (1.0 - kMinRoundGain) * best.rms;
  best = {round, rms, state->fitted, state->fitted_markers, state->motion, state->report, observed};
  if (small_gain && round < rounds) {
    // Kept, but the offsets now fit the take's noise more than its shape: on cmu_02_05
    // rounds 3-12 gained 0.01 mm each while the leave-one-marker-out mean error grew
    // from 9.7 to 12.5 mm.
    SkeletonFitEvent stopped = started;
    stopped.kind = SkeletonFitEvent::kStopped;
    stopped.rms = best.rms;
    events.Emit(stopped);
    return false;
  }
  return true;
}

// Scores `fit` (held_out_round.h) and adds it to the candidates; `round_index` is its
// entry in result->rounds.
Status AddCandidate(const RoundFit& fit, const MarkerSolveOptions& solve_options, const std::string& markers_path,
                    int round_index, RoundState* state, SkeletonFitResult* result) {
  double score = 0.0;
  const Status status = HeldOutRoundScore(fit.skeleton, fit.markers, fit.motion, fit.observed, solve_options,
                                          HeldOutRoundOptions(), &score);
  if (!status.ok()) return Status::Error(markers_path + ": round " + std::to_string(fit.round) + ": " + status.message());
  state->candidates.push_back(fit);
  state->held_out.push_back(score);
  if (round_index >= 0) result->rounds[round_index].held_out = score;
  return Status::Ok();
}

// The kept round's markers over a hinge (within the skin radius of the joint between two
// bones: a patella, an epicondyle, a marker over the wrist) offered the 50/50 blend on
// the hinge's two bones (HingeBlendCandidates) and decided by prediction on the last
// third of the kept round's frames, the blend's and the marker's own offsets fitted on the
// first two thirds (a time split inside the fit: a blend has six offset parameters to the
// single bone's three, and scored on the frames that fitted them it won where it later
// failed, BENCHMARKS.md, issue 36, h36j); a blend kept gets its offsets fitted on every
// frame. Nothing else of the round changes. Only a hinge that bends by hinge_min_bend in
// the first two thirds is offered: one that holds still there leaves the blend's offsets
// unidentified, and an elbow bending only in the take's last tenth had a forearm marker
// blended over it (BENCHMARKS.md, issue 36, h36k). A limb's blends are decided together,
// scored on every marker of the limb (ChooseLimbBlends): two blends on one arm, each
// decided on its own bones' markers, had flipped a wrist marker neither group held (h36i).
// After the rounds, not in them: offered in every attach round, the blends changed the
// rounds' path and moved markers they did not touch by 10-40 mm either way (BENCHMARKS.md,
// issue 36, h36i).
Status BlendOverHinges(const FitTake& fit, double max_bone_distance, MarkerSolveOptions solve, RoundFit* best,
                       std::vector<SkeletonFitBlend>* blended) {
  const int markers = best->markers.num_markers();
  const AttachmentByPredictionOptions defaults;
  std::vector<std::pair<int, int>> hinge = HingeBlendCandidates(
      best->skeleton, best->markers, max_bone_distance, defaults.hinge_fraction, defaults.hinge_dofs);
  // Decided on the last third of the frames with every candidate's offsets, the blend's and
  // the marker's own, fitted on the first two thirds: a blend's six offset parameters fitted
  // on the frames that score them won on its own fit frames and failed later (h36j).
  const int split = best->motion.num_frames() * 2 / 3;
  const bool held_out = split >= 1 && split < best->motion.num_frames();
  Motion early = best->motion;
  if (held_out) early.frames.resize(split);
  // Only over a hinge that bends where the offsets are fitted (else they are not identified).
  DropHingesThatHoldStill(early, defaults.hinge_min_bend, defaults.max_frames, &hinge);
  std::vector<AttachmentChoice> blend(markers), own(markers);
  bool any = false;
  for (int s = 0; s < markers; ++s) {
    if (hinge[s].first < 0) continue;
    blend[s] = {{hinge[s].first, 0.5, Eigen::Vector3d::Zero()}, {hinge[s].second, 0.5, Eigen::Vector3d::Zero()}};
    own[s] = best->markers.marker(s).attachments;
    any = true;
  }
  if (!any) return Status::Ok();
  CalibrationOptions calibration;
  calibration.max_bone_distance = max_bone_distance;
  std::vector<AttachmentChoice> early_blend = blend;
  MarkerSet given = best->markers;
  Observations scored = best->observed;
  if (held_out) {
    Status status = FitChoices(fit, best->skeleton, early, calibration, best->markers, &early_blend);
    if (status.ok()) status = FitChoices(fit, best->skeleton, early, calibration, best->markers, &own);
    if (!status.ok()) return status;
    std::vector<MarkerSpec> specs;
    for (int s = 0; s < markers; ++s) {
      specs.push_back(best->markers.marker(s));
      if (!own[s].empty()) specs.back().attachments = own[s];
      if (own[s].empty()) early_blend[s].clear();
    }
    status = MarkerSet::Create(best->skeleton, std::move(specs), &given);
    if (!status.ok()) return status;
    scored.erase(scored.begin(), scored.begin() + std::min<size_t>(split, scored.size()));
  }
  Status status = FitChoices(fit, best->skeleton, best->motion, calibration, best->markers, &blend);
  if (!status.ok()) return status;
  for (int s = 0; s < markers; ++s) {
    if (blend[s].empty()) early_blend[s].clear();
  }
  if (solve.rest_prior_needs_reference || !solve.rest_rotations.empty()) {
    solve.rest_rotations = MeanPose(best->skeleton, best->motion);
  }
  // A limb's blends together: one at a time, scored on every marker of the limb (h36k).
  std::vector<AttachmentMove> moves;
  status = ChooseLimbBlends(best->skeleton, scored, early_blend, solve, defaults, &given, &moves);
  if (!status.ok()) return status;
  std::vector<MarkerSpec> specs;
  for (int s = 0; s < markers; ++s) specs.push_back(best->markers.marker(s));
  for (const AttachmentMove& move : moves) {
    if (!move.moved) continue;
    specs[move.marker].attachments = blend[move.marker];  // Its offsets fitted on every frame.
    blended->push_back({best->markers.label(move.marker), best->skeleton.name(blend[move.marker][0].joint),
                        best->skeleton.name(blend[move.marker][1].joint)});
  }
  return MarkerSet::Create(best->skeleton, std::move(specs), &best->markers);
}

// The kept round: the latest candidate whose held-out score is within the tolerance of
// the lowest (KeptRound); the best by marker RMS when no round was a candidate.
// Returns the kept round's score (-1 when no round was a candidate).
double KeepHeldOutRound(RoundState* state) {
  const int kept = KeptRound(state->held_out, HeldOutRoundOptions().tolerance);
  if (kept >= 0) state->best = std::move(state->candidates[kept]);
  state->candidates.clear();
  return kept >= 0 ? state->held_out[kept] : -1.0;
}

// The kept round as the fitted subject: lone joints regauged, the checks run against the
// observations it was fitted to, its mean pose as the subject's rest prior.
// With --learn_weights: each marker's solve weight from a solve of the kept subject on the
// fitted frames (marker_weights.h), its own mean pose as the rest prior's reference.
Status LearnWeights(const SkeletonFitSettings& settings, MarkerSolveOptions solve_options,
                    const Observations& observed, SkeletonFitResult* result) {
  if (!(settings.learn_weights > 0.0)) return Status::Ok();
  Subject& subject = result->subject;
  if (!solve_options.rest_rotations.empty()) solve_options.rest_rotations = subject.mean_pose;
  MarkerWeightOptions options;
  options.min_weight = settings.learn_weights;
  Status status = LearnMarkerWeights(subject.skeleton, subject.markers, observed, solve_options, options,
                                     &result->weights);
  if (status.ok()) status = ApplyMarkerWeights(subject.skeleton, subject.markers, result->weights.weight, &subject.markers);
  return status;
}

// A held joint (no marker on it or below it: held_segments.h) never moved in the fit, so its
// mean over the fitted motion is the skeleton's zero rotation: for an ASF template a T-pose,
// which later solves would hold a sparse set's unobserved arms in (one pointing up from a
// leaning chest). It keeps the template's mean pose instead, the pose the template's actor
// held that joint in, matched by joint name.
void KeepTemplatePoseOfHeldJoints(const Subject& templ, Subject* subject) {
  const Skeleton& skeleton = subject->skeleton;
  if (templ.mean_pose.size() != static_cast<size_t>(templ.skeleton.num_joints())) return;
  const std::vector<bool> observed = ObservedJoints(skeleton, subject->markers);
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const int t = templ.skeleton.FindJoint(skeleton.name(j));
    if (!observed[j] && t >= 0) subject->mean_pose[j] = templ.mean_pose[t];
  }
}

Status KeepSubject(const SkeletonFitInputs& inputs, const FitTake& fit, const SkeletonFitSettings& settings,
                   const MarkerSolveOptions& solve_options, RoundState* state, SkeletonFitResult* result) {
  RoundFit& best = state->best;
  // A joint one marker alone constrains rests at its mean fitted pose (lone_joint_gauge.h):
  // the same fit, but a solve without that marker predicts it.
  std::vector<std::string> regauged;
  const Status status = FixLoneJointGauges(best.skeleton, &best.markers, &best.motion, &regauged);
  if (!status.ok()) return Status::Error(inputs.markers_path + ": " + status.message());
  // The checks see the kept model against the observations it was fitted to.
  result->kept_round = best.round;
  result->outlier_samples = static_cast<int>(state->template_outliers.size());
  result->motion = std::move(best.motion);
  result->motion.frame_rate = fit.take.trajectories.frame_rate;
  result->report = std::move(best.report);
  result->checks = CheckSubjectFit(best.skeleton, best.markers, best.observed, result->motion, fit.check_options);
  Subject& subject = result->subject;
  subject.name = inputs.templ.name.empty() ? "fitted" : "fitted from " + inputs.templ.name;
  subject.skeleton = std::move(best.skeleton);  // Inline: the fitted skeleton exists nowhere else.
  subject.markers = std::move(best.markers);
  result->held = FindHeldSegments(subject.skeleton, subject.markers);
  subject.axes = fit.mapping.axes;  // The detected ones when the markers were associated.
  subject.marker_scale = fit.mapping.marker_scale;
  subject.amc_fps = inputs.amc_fps;
  // The rest prior's reference in later solves of this subject (directions no marker fixes
  // settle at the pose the subject typically holds, not at zero rotations).
  subject.mean_pose = MeanPose(subject.skeleton, result->motion);
  KeepTemplatePoseOfHeldJoints(inputs.templ, &subject);
  return LearnWeights(settings, solve_options, best.observed, result);
}

}  // namespace

Status ValidateSkeletonFitSettings(const SkeletonFitSettings& s) {
  Status status = SkeletonFitSettingOptions().Validate(s);
  if (!status.ok()) return status;
  if (!(s.min_bone_scale > 0.0)) return Status::Error("--min_bone_scale: expected a value in (0, 1], got 0");
  if (TemplateLabelsGiven(s)) {
    std::vector<TemplateLabel> labels;
    return ReadTemplateLabels(s.template_labels, &labels);
  }
  return Status::Ok();
}

namespace {

// One fit of the take from inputs.templ (the rounds, the kept round, its blends);
// *held_out: the kept round's held-out score (-1 when no round was a candidate).
Status FitSubjectOnce(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                      const MarkerSolveOptions& solve_options, SkeletonFitResult* result,
                      const SkeletonFitCallback& callback, double* held_out) {
  const auto start = std::chrono::steady_clock::now();
  *result = SkeletonFitResult();
  *held_out = -1.0;
  Status status = ValidateSkeletonFitSettings(settings);
  if (!status.ok()) return status;
  const std::string& markers_path = inputs.markers_path;
  const bool from_subject = inputs.from_template_subject;
  const int rounds = settings.attach_rounds >= 0 ? settings.attach_rounds : (from_subject ? 12 : 0);
  result->attach_rounds = rounds;
  const Skeleton& skeleton = inputs.templ.skeleton;
  if (settings.max_skin_cm > 0.0 && !skeleton.unit().known()) {
    return Status::Error("the template skeleton's unit is unknown: give --skeleton_units (or --max_skin_cm=0)");
  }
  if (settings.fit_outlier_mm > 0.0 && !skeleton.unit().known()) {
    return Status::Error("the template skeleton's unit is unknown: give --skeleton_units (or --fit_outlier_mm=0)");
  }
  const double units_per_cm = skeleton.unit().known() ? 0.01 / skeleton.unit().metres_per_unit : 1.0;
  result->unit_known = skeleton.unit().known();
  result->mm_per_unit = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 1000.0 : 1.0;
  const FitEvents events(callback, start);
  FitTake fit;
  status = LoadFitTake(inputs, settings, units_per_cm, events, result, &fit);
  if (!status.ok()) return status;

  SkeletonFitOptions base_options = BaseFitOptions(settings, units_per_cm);
  base_options.held_limbs = fit.held_limbs;
  const double outlier_distance = settings.fit_outlier_mm * 0.1 * units_per_cm;
  RoundState state;
  state.fitted = skeleton;
  state.fitted_markers = fit.mapping.markers;
  state.scales.assign(skeleton.num_joints(), 1.0);
  for (int round = 0; round <= rounds; ++round) {
    Observations observed = fit.take.observed;
    MarkerSet round_markers = state.fitted_markers;
    if (round >= 2 && (state.best.round >= 1 || state.round0_complete)) StartFromBest(&state);
    if (round > 0) {
      status = AttachRound(fit, base_options.max_bone_distance, solve_options, round, markers_path, &state,
                           &round_markers, &observed);
      if (!status.ok()) return status;
    }
    const SkeletonFitOptions options =
        RoundOptions(base_options, settings, from_subject, round, outlier_distance, state.scales);
    const SkeletonFitEvent started =
        RoundStartEvent(round, rounds, round_markers.num_markers(), fit.frames, options.iterations);
    events.Emit(started);
    status = FitRound(fit, options, solve_options, round_markers, started, events, markers_path, &state, &observed,
                      result);
    if (!status.ok()) return status;
    if (round == 1 && state.round0_complete) {
      status = AddCandidate(state.best, solve_options, markers_path, 0, &state, result);
      if (!status.ok()) return status;
    }
    if (round >= 1) {
      const RoundFit fitted{round, state.report.rms.back(), state.fitted, state.fitted_markers, state.motion,
                            state.report, observed};
      status = AddCandidate(fitted, solve_options, markers_path, static_cast<int>(result->rounds.size()) - 1, &state,
                            result);
      if (!status.ok()) return status;
    }
    if (!KeepBestRound(round, rounds, observed, started, events, &state)) break;
  }
  *held_out = KeepHeldOutRound(&state);
  if (rounds > 0) {
    status = BlendOverHinges(fit, base_options.max_bone_distance, solve_options, &state.best, &result->hinge_blends);
    if (!status.ok()) return Status::Error(markers_path + ": " + status.message());
    SkeletonFitEvent blended;
    blended.kind = SkeletonFitEvent::kBlended;
    blended.markers = static_cast<int>(result->hinge_blends.size());
    for (const SkeletonFitBlend& b : result->hinge_blends) {
      blended.text += (blended.text.empty() ? "" : ", ") + b.marker + " on " + b.parent_joint + " + " + b.joint;
    }
    events.Emit(blended);
  }
  if (rounds > 0 && state.best.round != rounds) {
    SkeletonFitEvent kept;
    kept.kind = SkeletonFitEvent::kKept;
    kept.round = state.best.round;
    kept.rounds = rounds;
    kept.rms = state.best.rms;
    events.Emit(kept);
  }
  status = KeepSubject(inputs, fit, settings, solve_options, &state, result);
  if (!status.ok()) return status;
  result->seconds = Seconds(start);
  return Status::Ok();
}

}  // namespace

// The template's joints that lock a rotation axis nothing below them makes up, observed by
// at least three of the fitted subject's markers (locked_axes.h: an ASF foot's roll about
// its heel-toe axis), are freed and the take fitted again from that template; the freed fit
// is kept when its kept round's held-out score (held_out_round.h, on the fit's own frames
// only) is lower by more than 1 %. Decided by prediction, not by the markers seen: squat.c3d's and
// cmu_02_05's feet, whose markers follow the locked foot within 1-6 mm, lost 0.5-2.4 mm of
// time-split median with their feet freed (the attach rounds take other paths), and their
// held-out scores say so (BENCHMARKS.md, issue 36, h31n).
constexpr double kFreedAxesMinGain = 0.01;

Status FitSubjectToTake(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                        const MarkerSolveOptions& solve_options, SkeletonFitResult* result,
                        const SkeletonFitCallback& callback) {
  const auto start = std::chrono::steady_clock::now();
  double held_out = -1.0;
  Status status = FitSubjectOnce(inputs, settings, solve_options, result, callback, &held_out);
  if (!status.ok() || held_out < 0.0 || !settings.free_locked_axes) return status;
  const std::vector<int> locked = LockedAxisJoints(result->subject.skeleton, result->subject.markers);
  if (locked.empty()) return status;
  SkeletonFitInputs freed_inputs = inputs;
  status = FreeLockedAxes(inputs.templ.skeleton, locked, &freed_inputs.templ.skeleton);
  if (!status.ok()) return Status::Error(inputs.markers_path + ": " + status.message());
  std::vector<std::string> names;
  for (int j : locked) names.push_back(inputs.templ.skeleton.name(j));
  // The second fit takes as long as the first: its rounds are reported as they run, after a
  // line that says why; what the take's labels are was said once already.
  SkeletonFitCallback second;
  if (callback) {
    SkeletonFitEvent freeing;
    freeing.kind = SkeletonFitEvent::kFreeingAxes;
    for (const std::string& n : names) freeing.text += (freeing.text.empty() ? "" : ", ") + n;
    freeing.seconds = Seconds(start);
    callback(freeing);
    second = [&callback, offset = freeing.seconds](const SkeletonFitEvent& e) {
      const bool said = e.kind == SkeletonFitEvent::kTemplateLabels || e.kind == SkeletonFitEvent::kAbsentMarkers ||
                        e.kind == SkeletonFitEvent::kNotMarkers;
      if (said) return;
      SkeletonFitEvent shifted = e;
      shifted.seconds += offset;  // Since FitSubjectToTake started, as the first fit's.
      callback(shifted);
    };
  }
  SkeletonFitResult freed;
  double freed_held_out = -1.0;
  status = FitSubjectOnce(freed_inputs, settings, solve_options, &freed, second, &freed_held_out);
  if (!status.ok()) return status;
  // Kept when lower by more than the score's spread between fits that are alike (about 1 %,
  // held_out_round.h): a freed axis the take does not need then keeps the template's.
  if (freed_held_out >= 0.0 && freed_held_out < (1.0 - kFreedAxesMinGain) * held_out) {
    *result = std::move(freed);
    result->freed_axes = names;
  }
  result->locked_axes_held_out = {held_out, freed_held_out};
  result->seconds = Seconds(start);
  if (callback) {
    SkeletonFitEvent event;
    event.kind = SkeletonFitEvent::kFreedAxes;
    event.markers = static_cast<int>(result->freed_axes.size());
    for (const std::string& n : names) event.text += (event.text.empty() ? "" : ", ") + n;
    event.rms = held_out;
    event.rms_first = freed_held_out;
    event.seconds = result->seconds;
    callback(event);
  }
  return Status::Ok();
}

Status SkeletonFitCheckStatus(const SkeletonFitInputs& inputs, const SkeletonFitSettings& settings,
                              const SkeletonFitResult& result) {
  if (result.checks.ok() || settings.check != "fail") return Status::Ok();
  return Status::Error(inputs.markers_path + ": the fitted subject fails its checks (" + result.checks.failures[0] +
                       "); nothing written but the report (--check=warn writes it anyway)");
}

JsonObject SkeletonFitReportJson(const SkeletonFitInputs& inputs, const SkeletonFitResult& result) {
  const double mm = result.mm_per_unit;
  std::vector<JsonObject> round_json;
  for (const SkeletonFitRound& round : result.rounds) {
    std::vector<JsonValue> rms;
    for (double r : round.rms) rms.push_back(JsonValue(r * mm));
    JsonObject o;
    o.Add("round", round.round).Add("markers", round.markers).Add("rms_by_iteration", rms)
        .Add("outlier_samples", round.outlier_samples);
    if (round.held_out >= 0.0) o.Add("held_out_median", round.held_out * mm);
    round_json.push_back(o);
  }
  const Skeleton& fitted = result.subject.skeleton;
  std::vector<JsonObject> scale_json;
  for (int j = 1; j < fitted.num_joints(); ++j) {
    JsonObject o;
    o.Add("joint", fitted.name(j)).Add("scale", result.report.bone_scales[j]);
    scale_json.push_back(o);
  }
  std::vector<JsonObject> label_json;
  for (const TemplateLabel& label : result.template_labels) {
    JsonObject o;
    o.Add("template", label.templ).Add("take", label.take);
    label_json.push_back(o);
  }
  std::vector<JsonObject> not_marker_json;
  for (const auto& [label, reason] : result.not_markers) {
    JsonObject o;
    o.Add("label", label).Add("reason", reason);
    not_marker_json.push_back(o);
  }
  std::vector<JsonObject> blend_json;
  for (const SkeletonFitBlend& b : result.hinge_blends) {
    JsonObject o;
    o.Add("marker", b.marker).Add("parent_joint", b.parent_joint).Add("joint", b.joint);
    blend_json.push_back(o);
  }
  std::vector<JsonValue> freed_json;
  for (const std::string& j : result.freed_axes) freed_json.push_back(JsonValue(j));
  JsonObject json;
  if (result.associated) json.Add("association", AssociationJson(result));
  json.Add("markers", inputs.markers_path).Add("template", inputs.template_name)
      .Add("template_labels", label_json).Add("template_labels_map", result.template_labels_map)
      .Add("not_markers", not_marker_json)
      .Add("frames", result.frames).Add("frame_stride", result.frame_stride)
      .Add("attach_rounds", result.attach_rounds).Add("kept_round", result.kept_round)
      .Add("seconds", result.seconds)
      .Add(result.unit_known ? "rms_mm" : "rms", result.report.rms.back() * mm)
      .Add("outlier_samples", result.outlier_samples)
      .Add("rounds", round_json).Add("hinge_blends", blend_json).Add("freed_axes", freed_json).Add("bone_scales", scale_json)
      .Add("checks", ChecksJson(result.checks));
  std::vector<JsonValue> held;
  for (const std::string& top : result.held.tops) held.push_back(JsonValue(top));
  JsonObject held_json;
  held_json.Add("tops", held).Add("joints", result.held.joints);
  json.Add("held_segments", held_json);
  return json;
}

int FitFrameStride(int max_frames, int frames) {
  return max_frames > 0 && frames > max_frames ? (frames + max_frames - 1) / max_frames : 1;
}

Status CheckSkeletonFitInputsGiven(bool template_subject, bool skeleton, bool markerset, bool skeleton_units,
                                   bool markers) {
  if (template_subject && (skeleton || markerset || skeleton_units)) {
    return Status::Error(std::string("--template_subject and --") +
                         (skeleton ? "skeleton" : markerset ? "markerset" : "skeleton_units") +
                         " both given: the template subject holds the skeleton and marker set");
  }
  if (!markers || (!template_subject && skeleton != markerset)) {
    return Status::Error("--markers and either --template_subject, or --skeleton and --markerset, or none of them "
                         "(the shipped template) are required");
  }
  return Status::Ok();
}

Status LoadSkeletonFitTemplate(const std::string& template_subject, const std::string& skeleton,
                               const std::string& markerset, const std::string& skeleton_units,
                               SkeletonFitInputs* inputs) {
  Status status = CheckSkeletonFitInputsGiven(!template_subject.empty(), !skeleton.empty(), !markerset.empty(),
                                              !skeleton_units.empty(), !inputs->markers_path.empty());
  if (!status.ok()) return status;
  if (template_subject.empty() && skeleton.empty()) {
    // The shipped template: a subject, as a template subject file is.
    inputs->from_template_subject = true;
    inputs->template_name = DefaultTemplateName();
    return DefaultTemplateSubject(&inputs->templ);
  }
  inputs->from_template_subject = !template_subject.empty();
  if (inputs->from_template_subject) {
    inputs->template_name = template_subject;
    return ReadSubject(template_subject, &inputs->templ);
  }
  inputs->template_name = skeleton;
  status = ReadSkeletonFile(skeleton, &inputs->templ.skeleton);
  if (status.ok()) status = SetSkeletonUnits(skeleton_units, &inputs->templ.skeleton);
  if (status.ok()) status = ReadMarkerSet(markerset, inputs->templ.skeleton, &inputs->templ.markers);
  return status;
}

std::string SkeletonFitEventLine(const SkeletonFitEvent& e, const Skeleton& templ, bool* to_stdout) {
  const bool known = templ.unit().known();
  const double mm = known ? templ.unit().metres_per_unit * 1000.0 : 1.0;
  const char* unit = known ? "mm" : "skeleton units";
  std::string line;
  *to_stdout = false;
  switch (e.kind) {
    case SkeletonFitEvent::kTemplateLabels:
      AppendF(&line, "fit_skeleton: template labels: %d pairs from %s\n", e.markers, e.text.c_str());
      break;
    case SkeletonFitEvent::kAbsentMarkers:
      AppendF(&line, "fit_skeleton: not in the file, left out: %s\n", e.text.c_str());
      break;
    case SkeletonFitEvent::kNotMarkers:
      AppendF(&line, "fit_skeleton: not markers, left out: %s\n", e.text.c_str());
      break;
    case SkeletonFitEvent::kRoundStart:
      AppendF(&line, "fit_skeleton: round %d/%d: %d markers, %d frames, %d iterations (%.0f s so far)\n", e.round,
              e.rounds, e.markers, e.frames, e.iterations, e.seconds);
      break;
    case SkeletonFitEvent::kFrames:
      break;
    case SkeletonFitEvent::kIteration:
      AppendF(&line, "  iteration %d: marker RMS %.2f %s (%.0f s)\n", e.iteration, e.rms * mm, unit, e.seconds);
      break;
    case SkeletonFitEvent::kRoundDone:  // The report's "rounds" holds the same figures.
      *to_stdout = true;
      AppendF(&line, "round %d: %d markers, marker RMS %.2f -> %.2f %s\n", e.round, e.markers, e.rms_first * mm,
              e.rms * mm, unit);
      break;
    case SkeletonFitEvent::kStopped:
      AppendF(&line, e.rms > 0.0 ? "fit_skeleton: round %d improved by less than 1 %%; stopping\n"
                                 : "fit_skeleton: round %d did not improve; stopping\n", e.round);
      break;
    case SkeletonFitEvent::kKept:
      AppendF(&line, "fit_skeleton: keeping round %d (marker RMS %.2f %s; the latest round within 5 %% of the lowest held-out leave-one-out median)\n",
              e.round, e.rms * mm, unit);
      break;
    case SkeletonFitEvent::kBlended:
      AppendF(&line, "fit_skeleton: markers blended 50/50 over a hinge: %d%s%s\n", e.markers, e.text.empty() ? "" : ": ",
              e.text.c_str());
      break;
    case SkeletonFitEvent::kFreeingAxes:
      AppendF(&line, "fit_skeleton: fitting again with the locked axis of %s freed (kept if it predicts the held-out "
              "markers better)\n", e.text.c_str());
      break;
    case SkeletonFitEvent::kFreedAxes:
      AppendF(&line, "fit_skeleton: %s with the locked axis of %s (held-out median %.2f %s, %.2f %s without)\n",
              e.markers > 0 ? "kept the fit" : "not kept: the fit", e.text.c_str(), e.rms_first * mm, unit,
              e.rms * mm, unit);
      break;
  }
  return line;
}

std::string SkeletonFitSummary(const SkeletonFitResult& result) {
  const SubjectChecks& checks = result.checks;
  const Skeleton& fitted = result.subject.skeleton;
  std::string text;
  if (result.associated) {
    const MarkerAssociation& a = result.association;
    int fitted = 0;
    for (const std::string& joint : result.association_joints) fitted += !joint.empty();
    AppendF(&text, "association: %zu markers in %zu rigid groups, %d on template joints, %zu points left out as no "
            "markers; up %s, %s%s, body %.2f m\n", a.markers.size(), a.clusters.size(), fitted, a.excluded.size(),
            a.UpName().c_str(), a.unit.name.c_str(), a.unit_from_data ? " (from the data)" : "", a.height_m);
  }
  AppendF(&text, "checks: marker RMS %.1f mm, max marker-to-bone %.1f cm (%s), max marker-to-joint %.1f cm, torso "
          "direction error mean %.1f max %.1f deg over %d frames, left/right asymmetry %.1f %%%s%s\n",
          checks.rms_mm, checks.max_bone_distance_cm, checks.farthest_marker.c_str(), checks.max_joint_distance_cm,
          checks.torso_error_mean_deg, checks.torso_error_max_deg, checks.torso_frames, 100.0 * checks.max_asymmetry,
          checks.least_symmetric_pair.empty() ? "" : (" (" + checks.least_symmetric_pair + ")").c_str(),
          checks.ok() ? ", passed" : "");
  text += "bone scales:";
  for (int j = 1; j < fitted.num_joints(); ++j) {
    if (std::abs(result.report.bone_scales[j] - 1.0) > 1e-9) {
      AppendF(&text, " %s %.3f", TerminalText(fitted.name(j)).c_str(), result.report.bone_scales[j]);
    }
  }
  if (!result.held.tops.empty()) {
    std::string tops;
    for (const std::string& top : result.held.tops) tops += (tops.empty() ? "" : ", ") + TerminalText(top);
    AppendF(&text, "\nheld at the template's mean pose, no marker on them or below them: %s (%d joints)", tops.c_str(),
            result.held.joints);
  }
  const int outliers = result.outlier_samples;
  const std::string left_out = outliers > 0 ? " (" + std::to_string(outliers) + " outlier samples left out)" : "";
  AppendF(&text, "\nfit: %d markers, marker RMS %.2f %s%s, %.1f s\n", result.subject.markers.num_markers(),
          result.report.rms.back() * result.mm_per_unit, result.unit_known ? "mm" : "skeleton units", left_out.c_str(),
          result.seconds);
  return text;
}

}  // namespace mocapsolve
