#include "settings/repair_settings.h"

#include <cmath>

#include "kinematics/rotation.h"

namespace mocapsolve {

const OptionGroup<SolverSettings>& RepairSolverOptions() {
  static const OptionGroup<SolverSettings>* const group = new OptionGroup<SolverSettings>(SolverOptions().WithDefault(
      "solver", "dls",
      "dls | dls_generic | ceres: who solves the per-frame steps (the naive solve Y and the re-solve); "
      "dls, the lean tree kernel, is the default here."));
  return *group;
}

void SetRepairRestRotations(const QuaternionVector& mean_pose, RepairOptions* options) {
  options->naive.rest_rotations = mean_pose;
}

Status RepairOptionsFromSettings(const RepairSettings& settings, const SolverSettings& solver,
                                 const Skeleton& skeleton, RepairOptions* options) {
  if (!skeleton.unit().known()) {
    return Status::Error("the skeleton's unit is unknown; give --skeleton_units");
  }
  const double units_per_cm = 0.01 / skeleton.unit().metres_per_unit;
  const double units_per_mm = 0.1 * units_per_cm;
  Status status = MarkerSolveOptionsFromSettings(solver, skeleton.unit(), &options->naive);
  if (status.ok()) status = ClipSolveOptionsFromSettings(solver, &options->reference);
  if (!status.ok()) return status;
  if (settings.reference == "tracker") {
    options->reference_kind = ReferenceKind::kTracker;
  } else if (settings.reference == "clip") {
    options->reference_kind = ReferenceKind::kClip;
  } else {
    return Status::Error("--reference: unknown '" + settings.reference + "' (tracker, clip)");
  }
  options->reference.loss = settings.reference_loss;
  options->reference.loss_scale = settings.reference_loss_cm * units_per_cm;
  // Threads change the speed only, never the result (a batch runs takes side by side, one each).
  options->parallel = solver.num_threads >= 2;
  options->tracker = options->naive;
  // The robust reference judges the samples: no pull toward the subject's mean pose, a pose of
  // another take (with it, cmu_02_05's small-error precision fell 0.928 -> 0.901).
  options->tracker.rest_rotation_weight = 0.0;
  options->tracker.loss = settings.reference_loss;
  options->tracker.loss_scale = settings.reference_loss_cm * units_per_cm;
  options->tracker.prior_rotation_weight = settings.tracker_prior_weight * units_per_mm;
  options->tracker.prior_translation_weight = settings.tracker_translation_prior;
  options->tracker.dls.function_tolerance = settings.tracker_function_tolerance;
  options->tracker.ceres.function_tolerance = settings.tracker_function_tolerance;
  options->dp_max = settings.dp_max_cm * units_per_cm;
  options->dr_max_rad = DegToRad(settings.dr_max_deg);
  options->outlier_distance = settings.outlier_cm * units_per_cm;
  if (settings.outliers != "robust" && settings.outliers != "fixed") {
    return Status::Error("--outliers: unknown '" + settings.outliers + "' (robust, fixed)");
  }
  options->robust_outliers = settings.outliers == "robust";
  options->outlier_mads = settings.outlier_mads;
  options->outlier_min_distance = settings.outlier_min_cm * units_per_cm;
  options->undo_swaps = settings.undo_swaps;
  options->swap_radius = settings.swap_radius_cm * units_per_cm;
  options->swap_min_frames = settings.swap_min_frames;
  options->assign_unlabelled = settings.assign_unlabelled;
  options->unlabelled_min_distance = settings.unlabelled_min_cm * units_per_cm;
  options->unlabelled_max_distance = settings.unlabelled_max_cm * units_per_cm;
  options->unlabelled_min_frames = settings.unlabelled_min_frames;
  options->trim_max = settings.trim_max;
  options->small_track = settings.small_track;
  options->small_gap = settings.small_gap;
  options->velocity_clamp = settings.vel_clamp * units_per_cm;
  options->edge_samples = settings.edge_samples;
  if (settings.fill == "blend") {
    options->fill = GapFillKind::kBlend;
  } else if (settings.fill == "kriging") {
    options->fill = GapFillKind::kKriging;
  } else {
    return Status::Error("--fill: unknown '" + settings.fill + "' (blend, kriging)");
  }
  options->fill_samples = settings.fill_samples;
  options->refit_reference = settings.refit_reference;
  options->refit_rough_factor = settings.refit_rough_factor;
  options->rough_extension_factor = settings.rough_extension_factor;
  std::string error;
  if (!options->reference.IsValid(&error) || !options->tracker.IsValid(&error)) {
    return Status::Error(error);
  }
  if (!(options->outlier_distance > 0.0)) return Status::Error("--outlier_cm must be positive");
  if (!(settings.outlier_mads > 0.0) || !std::isfinite(settings.outlier_mads)) {
    return Status::Error("--outlier_mads must be positive and finite");
  }
  if (!(settings.outlier_min_cm >= 0.0) || !std::isfinite(settings.outlier_min_cm)) {
    return Status::Error("--outlier_min_cm must be >= 0 and finite");
  }
  if (!(settings.swap_radius_cm > 0.0) || !std::isfinite(settings.swap_radius_cm)) {
    return Status::Error("--swap_radius_cm must be positive and finite");
  }
  if (settings.swap_min_frames < 1) return Status::Error("--swap_min_frames must be >= 1");
  if (!(settings.unlabelled_min_cm > 0.0) || !std::isfinite(settings.unlabelled_max_cm) ||
      !(settings.unlabelled_max_cm >= settings.unlabelled_min_cm)) {
    return Status::Error("--unlabelled_min_cm must be positive and --unlabelled_max_cm finite and at least it");
  }
  if (settings.unlabelled_min_frames < 1) return Status::Error("--unlabelled_min_frames must be >= 1");
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

}  // namespace mocapsolve
