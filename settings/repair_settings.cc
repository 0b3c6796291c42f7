#include "settings/repair_settings.h"

#include <cmath>

#include "kinematics/rotation.h"

namespace mocapsolve {

const OptionGroup<RepairSettings>& RepairSettingOptions() {
  using S = RepairSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::dp_max_cm, "dp_max_cm", "cm",
           "A joint farther than this (cm) from the robust reference is bad "
           "(thesis 3.4.2: 10 cm).")
      .Add(&S::dr_max_deg, "dr_max_deg", "deg",
           "A joint turned more than this (degrees) from the reference is bad "
           "(thesis: 30).")
      .Add(&S::outlier_cm, "outlier_cm", "cm",
           "With --outliers=fixed, a marker sample farther than this (cm) from its "
           "reconstruction on the reference is an outlier (chapter 3's rule); with robust, the cap "
           "of every marker's gate.")
      .Add(&S::outliers, "outliers",
           "How outliers are found: robust (each marker judged against its own "
           "typical residual over the take: gate = median deviation + --outlier_mads MADs, at "
           "least --outlier_min_cm, at most --outlier_cm; finds 1-4 cm jumps on markers that are "
           "normally within mm and spares markers on loose tissue or with an offset error) | fixed "
           "(--outlier_cm from the reconstruction).",
           {"robust", "fixed"})
      .Add(&S::outlier_mads, "outlier_mads", "",
           "Robust outlier gate: robust standard deviations (1.4826 MAD) "
           "past the marker's median deviation.")
      .Add(&S::outlier_min_cm, "outlier_min_cm", "cm",
           "Robust outlier gate: never below this (cm).")
      .Add(&S::undo_swaps, "undo_swaps",
           "Find label swaps (a sample far from its own marker's prediction and "
           "close to that of a nearby marker left without a good sample) and relabel them "
           "instead of cutting and refilling; reported as 'swaps'.")
      .Add(&S::swap_radius_cm, "swap_radius_cm", "cm",
           "Markers whose predicted positions are this close (cm) may "
           "swap labels.")
      .Add(&S::swap_min_frames, "swap_min_frames", "frames",
           "A swap must persist this many consecutive frames.")
      .Add(&S::assign_unlabelled, "assign_unlabelled",
           "Label unlabelled points (C3D '*52'): a point becomes the "
           "sample of a missing marker where it lies within the marker's gate around its prediction "
           "and continues the marker's track, one to one per frame; reported as 'unlabelled_assigned'.")
      .Add(&S::unlabelled_min_cm, "unlabelled_min_cm", "cm",
           "Unlabelled assignment gate (the marker's median deviation + "
           "--outlier_mads MADs): never below this (cm).")
      .Add(&S::unlabelled_max_cm, "unlabelled_max_cm", "cm",
           "Unlabelled assignment gate: never above this (cm).")
      .Add(&S::unlabelled_min_frames, "unlabelled_min_frames", "frames",
           "An assigned run of frames that continues no observed "
           "sample of the marker needs at least this many frames.")
      .Add(&S::trim_max, "trim_max", "frames",
           "Frames trimmed at most on each side of a gap (thesis: 120).")
      .Add(&S::small_track, "small_track", "frames",
           "Valid runs of at most this many frames between gaps are dropped.")
      .Add(&S::small_gap, "small_gap", "frames",
           "Gaps of at most this many frames are filled by a plain cubic.")
      .Add(&S::vel_clamp, "vel_clamp", "cm/frame",
           "Clamp of the offset velocity at gap edges, in cm per frame "
           "(the thesis' 0.25; its unit is not stated, its data are in cm).")
      .Add(&S::edge_samples, "edge_samples", "samples",
           "Samples beyond each gap edge that the refill's offset velocity is "
           "fitted to (a least-squares line; 2 = the thesis' one-sided difference, which a jittery "
           "marker throws off; 1 = no offset velocity: the fill blends the two edge offsets, "
           "which measured best on real takes, BENCHMARKS.md).")
      .Add(&S::fill, "fill",
           "How a gap is filled from the reference X^: kriging (the offset from "
           "X^ modelled per marker as mean + exponentially correlated process + white noise, "
           "estimated from the take; the fill is its conditional mean given --fill_samples samples "
           "on each side) | blend (X^ plus a blend from one edge's offset to the other's, Algorithm 3).",
           {"blend", "kriging"})
      .Add(&S::fill_samples, "fill_samples", "samples",
           "--fill=kriging: offset samples conditioned on per gap side.")
      .Add(&S::refit_reference, "refit_reference",
           "With --reference=tracker: refit X^ without the samples found "
           "bad (it leaned toward them) and fill smooth bad runs (fly-off, ghost) and gaps from it; "
           "rough runs (noise, jitter) are filled from X^ as solved.")
      .Add(&S::refit_rough_factor, "refit_rough_factor", "",
           "A bad run is rough when its median |second "
           "difference| exceeds this many times the marker's own.")
      .Add(&S::rough_extension_factor, "rough_extension_factor", "",
           "A rough bad run is extended over the "
           "samples beside it whose residual |second difference| exceeds this many times the marker's "
           "median and a tenth of the gates' floor (a noise run cut whole; at most --trim_max per side; "
           "0: off).")
      .Add(&S::carry_joints, "carry_joints",
           "Where a joint loses the markers that observe its rotation (at least 2 of them missing, "
           "fewer than 3 and fewer than half left, and no marker of its own bone left that fixes its "
           "degrees of freedom: a hidden foot, hand or head), carry it across those frames in joint "
           "space: along the same joint elsewhere in the take where the joints still seen moved "
           "alike (a stride earlier or later), bent to meet the poses solved on both sides, else a "
           "log-quaternion Hermite between those poses with velocities matched; solve them again "
           "pulled toward the carried pose, and refill the hidden markers from that motion; the report lists the joints carried and their frames.")
      .Add(&S::reference, "reference",
           "The robust reference Y^: tracker (frame by frame, robust loss, "
           "pulled toward the previous frame; runs beside the naive solve) | clip (the "
           "whole-clip solve with a robust loss and smoothness; ~10x slower).",
           {"tracker", "clip"})
      .Add(&S::reference_loss, "reference_loss",
           "Robust loss of the reference solve: cauchy | huber.")
      .Add(&S::reference_loss_cm, "reference_loss_cm", "cm",
           "Where the reference solve's loss bends (cm).")
      .Add(&S::tracker_prior_weight, "tracker_prior_weight", "mm/rad",
           "Tracker reference: pull of each joint rotation toward "
           "the previous frame, mm per radian (the naive solve's is --prior_weight).")
      .Add(&S::tracker_translation_prior, "tracker_translation_prior", "",
           "Tracker reference: pull of the root translation "
           "toward the previous frame (residual per unit of displacement).")
      .Add(&S::tracker_function_tolerance, "tracker_function_tolerance", "",
           "Tracker reference: stop when the relative cost "
           "change is below this. The reference only has to show where the markers broke: on "
           "02_01 1e-4 instead of 1e-6 leaves the repaired solve as good (0.170 vs 0.176 cm) and "
           "makes repair 1.6x faster.");
  return *group;
}

const OptionGroup<SolverSettings>& RepairSolverOptions() {
  static const OptionGroup<SolverSettings>* const group = new OptionGroup<SolverSettings>(
      SolverOptions().Without("mode"));
  return *group;
}

const OptionGroup<SolverSettings>& EvaluateSolverOptions() {
  static const OptionGroup<SolverSettings>* const group = new OptionGroup<SolverSettings>(
      RepairSolverOptions().WithDefault(
          "num_threads", "2",
          "Threads: leave_one_out solves this many markers at once; repair runs its solves on two threads when "
          ">= 2. Speed only: the results do not depend on it."));
  return *group;
}

void SetRepairRestRotations(const QuaternionVector& mean_pose, RepairOptions* options) {
  options->naive.rest_rotations = mean_pose;
}

Status RepairOptionsFromSettings(const RepairSettings& settings, const SolverSettings& solver,
                                 const Skeleton& skeleton, RepairOptions* options) {
  Status checked = RepairSettingOptions().Validate(settings);
  if (!checked.ok()) return checked;
  if (!skeleton.unit().known()) {
    return Status::Error("the skeleton's unit is unknown; give --skeleton_units");
  }
  const double units_per_cm = 0.01 / skeleton.unit().metres_per_unit;
  const double units_per_mm = 0.1 * units_per_cm;
  Status status = MarkerSolveOptionsFromSettings(solver, skeleton.unit(), &options->naive);
  if (status.ok()) status = ClipSolveOptionsFromSettings(solver, &options->reference);
  if (!status.ok()) return status;
  // The string options are one of their declared choices (checked above).
  options->reference_kind = settings.reference == "clip" ? ReferenceKind::kClip : ReferenceKind::kTracker;
  options->reference.loss = settings.reference_loss;
  options->reference.loss_scale = settings.reference_loss_cm * units_per_cm;
  // Threads change the speed only, never the result (a batch runs takes side by side, one each).
  options->parallel = solver.num_threads >= 2;
  options->tracker = options->naive;
  // The robust reference judges the samples: no pull toward the subject's mean pose, a pose of
  // another take (with it, cmu_02_05's small-error precision fell 0.928 -> 0.901).
  options->tracker.rest_rotation_weight = options->tracker.hidden_rotation_weight = 0.0;
  options->tracker.loss = settings.reference_loss;
  options->tracker.loss_scale = settings.reference_loss_cm * units_per_cm;
  options->tracker.prior_rotation_weight = settings.tracker_prior_weight * units_per_mm;
  options->tracker.prior_translation_weight = settings.tracker_translation_prior;
  options->tracker.dls.function_tolerance = settings.tracker_function_tolerance;
  options->tracker.ceres.function_tolerance = settings.tracker_function_tolerance;
  options->dp_max = settings.dp_max_cm * units_per_cm;
  options->dr_max_rad = DegToRad(settings.dr_max_deg);
  options->outlier_distance = settings.outlier_cm * units_per_cm;
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
  options->fill = settings.fill == "blend" ? GapFillKind::kBlend : GapFillKind::kKriging;
  options->fill_samples = settings.fill_samples;
  options->refit_reference = settings.refit_reference;
  options->refit_rough_factor = settings.refit_rough_factor;
  options->rough_extension_factor = settings.rough_extension_factor;
  options->carry_joints = settings.carry_joints;
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
