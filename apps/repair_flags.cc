#include "apps/repair_flags.h"

#include <gflags/gflags.h>

#include "apps/solver_flags.h"
#include "kinematics/rotation.h"

DEFINE_double(dp_max_cm, 10.0, "A joint farther than this (cm) from the robust reference is bad "
              "(thesis 3.4.2: 10 cm).");
DEFINE_double(dr_max_deg, 30.0, "A joint turned more than this (degrees) from the reference is bad "
              "(thesis: 30).");
DEFINE_double(outlier_cm, 4.0, "A marker sample farther than this (cm) from its reconstruction on "
              "the reference is an outlier (the thesis takes outliers from its neural solver; a "
              "swap with a neighbour moves a marker by a few cm, below --dp_max_cm).");
DEFINE_int32(trim_max, 120, "Frames trimmed at most on each side of a gap (thesis: 120).");
DEFINE_int32(small_track, 120, "Valid runs of at most this many frames between gaps are dropped.");
DEFINE_int32(small_gap, 5, "Gaps of at most this many frames are filled by a plain cubic.");
DEFINE_double(vel_clamp, 0.25, "Clamp of the offset velocity at gap edges, in cm per frame "
              "(the thesis' 0.25; its unit is not stated, its data are in cm).");
DEFINE_string(reference, "tracker", "The robust reference Y^: tracker (frame by frame, robust loss, "
              "pulled toward the previous frame; runs beside the naive solve) | clip (the "
              "whole-clip solve with a robust loss and smoothness; ~10x slower).");
DEFINE_string(reference_loss, "cauchy", "Robust loss of the reference solve: cauchy | huber.");
DEFINE_double(reference_loss_cm, 1.0, "Where the reference solve's loss bends (cm).");
DEFINE_double(tracker_prior_weight, 20.0, "Tracker reference: pull of each joint rotation toward "
              "the previous frame, mm per radian (the naive solve's is --prior_weight).");
DEFINE_double(tracker_translation_prior, 0.0, "Tracker reference: pull of the root translation "
              "toward the previous frame (residual per unit of displacement).");

DEFINE_double(tracker_function_tolerance, 1e-4, "Tracker reference: stop when the relative cost "
              "change is below this. The reference only has to show where the markers broke: on "
              "02_01 1e-4 instead of 1e-6 leaves the repaired solve as good (0.170 vs 0.176 cm) and "
              "makes repair 1.6x faster.");

namespace mocapsolve {

const char* const kRepairFlagNames =
    "dp_max_cm,dr_max_deg,outlier_cm,trim_max,small_track,small_gap,vel_clamp,reference,reference_loss,"
    "reference_loss_cm,tracker_prior_weight,tracker_translation_prior,tracker_function_tolerance";

Status RepairOptionsFromFlags(const Skeleton& skeleton, RepairOptions* options) {
  if (!skeleton.unit().known()) {
    return Status::Error("the skeleton's unit is unknown; give --skeleton_units");
  }
  const double units_per_cm = 0.01 / skeleton.unit().metres_per_unit;
  const double units_per_mm = 0.1 * units_per_cm;
  // Repair solves every frame two or three times: the DLS path unless asked otherwise.
  const bool solver_given = !gflags::GetCommandLineFlagInfoOrDie("solver").is_default;
  const std::string solver = FLAGS_solver;
  if (!solver_given) FLAGS_solver = "dls";
  Status status = MarkerSolveOptionsFromFlags(skeleton.unit(), &options->naive);
  FLAGS_solver = solver;
  if (status.ok()) status = ClipSolveOptionsFromFlags(&options->reference);
  if (!status.ok()) return status;
  if (FLAGS_reference == "tracker") {
    options->reference_kind = ReferenceKind::kTracker;
  } else if (FLAGS_reference == "clip") {
    options->reference_kind = ReferenceKind::kClip;
  } else {
    return Status::Error("--reference: unknown '" + FLAGS_reference + "' (tracker, clip)");
  }
  options->reference.loss = FLAGS_reference_loss;
  options->reference.loss_scale = FLAGS_reference_loss_cm * units_per_cm;
  // Threads change the speed only, never the result (a batch runs takes side by side, one each).
  options->parallel = FLAGS_num_threads >= 2;
  options->tracker = options->naive;
  options->tracker.loss = FLAGS_reference_loss;
  options->tracker.loss_scale = FLAGS_reference_loss_cm * units_per_cm;
  options->tracker.prior_rotation_weight = FLAGS_tracker_prior_weight * units_per_mm;
  options->tracker.prior_translation_weight = FLAGS_tracker_translation_prior;
  options->tracker.dls.function_tolerance = FLAGS_tracker_function_tolerance;
  options->tracker.ceres.function_tolerance = FLAGS_tracker_function_tolerance;
  options->dp_max = FLAGS_dp_max_cm * units_per_cm;
  options->dr_max_rad = DegToRad(FLAGS_dr_max_deg);
  options->outlier_distance = FLAGS_outlier_cm * units_per_cm;
  options->trim_max = FLAGS_trim_max;
  options->small_track = FLAGS_small_track;
  options->small_gap = FLAGS_small_gap;
  options->velocity_clamp = FLAGS_vel_clamp * units_per_cm;
  std::string error;
  if (!options->reference.IsValid(&error) || !options->tracker.IsValid(&error)) {
    return Status::Error(error);
  }
  if (!(options->outlier_distance > 0.0)) return Status::Error("--outlier_cm must be positive");
  if (!options->IsValid(&error)) return Status::Error(error);
  return Status::Ok();
}

}  // namespace mocapsolve
