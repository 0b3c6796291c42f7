// Evaluation of marker repair against the gap fills it improves on (issue 4; the
// analogue of the thesis' Table 1).
//
// From clean markers C and a corrupted copy X with its damage mask (signal/
// marker_corruption.h), each method produces markers and a kinematic solution:
//   original        X as it is (gaps stay missing), solved per frame;
//   polynomial      X's gaps filled by the naive cubic Hermite, solved;
//   linear          X's gaps filled linearly, solved;
//   pca             X's gaps filled by iterative PCA (Gloersen & Federolf 2016), solved;
//   reference only  the robust reference: its solution Y^ and markers X^ = LBS(Y^, Z);
//   ours            RepairMarkers (marker_repair.h): its repaired markers and Y-.
// and is scored against the per-frame solution of C (the "truth" kinematics):
//   joint_position_error   mean over frames and joints of |p_j - p_j*| (skeleton units);
//   joint_rotation_error   mean of the angle between global joint rotations (radians);
//   marker errors          |x - c| over the damaged samples the method has a value for
//                          (mean, RMS, max; skeleton units), and how many it covers;
//   velocity_jump          mean over the edges of damaged runs of |v_in - v_out|, the
//                          change of per-frame velocity across the edge (units/frame);
//                          the "clean" row gives the same figure on C, the natural one;
//   detection              which samples the method changed, against the mask: a sample
//                          observed in X is "detected" when the method's marker differs
//                          from it (repair returns unflagged samples bit for bit); recall
//                          per damage kind (for gaps: the share filled; for unlabelled
//                          samples, the share restored: the method's marker equals the
//                          clean sample bit for bit, which only a relabelling achieves), and
//                          precision = damaged / all changed observed samples;
//   relabels               (ours) unlabelled samples the labelling stage gave back to the
//                          marker they came from (the restored ones above are those of them
//                          that no later stage cut, such as trimming beside a gap), and those
//                          it gave to another marker.
// All methods solve with options.naive, so the differences come from the markers.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_REPAIR_EVALUATION_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_REPAIR_EVALUATION_H_

#include <string>
#include <vector>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/marker_repair/marker_repair.h"
#include "signal/marker_corruption.h"

namespace mocapsolve {

struct RepairEvaluationRow {
  std::string method;
  double joint_position_error = 0.0;  // Skeleton units.
  double joint_rotation_error = 0.0;  // Radians.
  double marker_error_mean = 0.0, marker_error_rms = 0.0, marker_error_max = 0.0;
  int damaged_samples = 0, covered_samples = 0;
  // Per kind of damage (kDamageKinds' order): the mean marker error (0 where none
  // covered), the damaged samples, and those the method detected (see above).
  double kind_error[kNumDamageKinds] = {};
  int kind_samples[kNumDamageKinds] = {};
  int kind_detected[kNumDamageKinds] = {};
  int unlabelled_assigned_samples = 0;  // Unlabelled samples assigned to their own marker (ours)...
  int unlabelled_false_samples = 0;     // ...and to another one.
  int changed_samples = 0;          // Observed samples of X the method changed...
  int changed_undamaged_samples = 0;  // ...of which undamaged: false detections.
  double velocity_jump = 0.0;  // Skeleton units per frame.
  double seconds = 0.0;        // Fill + solve.

  double Recall(int kind) const {
    return kind_samples[kind] > 0 ? static_cast<double>(kind_detected[kind]) / kind_samples[kind] : 1.0;
  }
  double Precision() const {
    return changed_samples > 0 ? 1.0 - static_cast<double>(changed_undamaged_samples) / changed_samples : 1.0;
  }
};

using MarkerObservations = std::vector<std::vector<Eigen::Vector3d>>;  // [frame][marker]

// clean and corrupted in model units (marker_observations.h), mask[frame][marker] as
// CorruptMarkers writes it. Rows: "clean" (the truth's own velocity jump), then the six
// methods in the order above.
// `unlabelled` (optional): the unlabelled damage's tracks (model units), given to the
// repair as the take's unlabelled points.
Status EvaluateRepair(const Skeleton& skeleton, const MarkerSet& markers,
                      const MarkerObservations& clean, const MarkerObservations& corrupted,
                      const CorruptionMask& mask, const RepairOptions& options,
                      std::vector<RepairEvaluationRow>* rows, const UnlabelledDamage* unlabelled = nullptr);

// One trial: `clean` damaged by CorruptMarkers(damage) (in the skeleton's units), then
// EvaluateRepair. `evaluate` and the Python module run trials with seeds seed, seed+1, ...
Status EvaluateRepairTrial(const Skeleton& skeleton, const MarkerSet& markers, const MarkerObservations& clean,
                           const CorruptionOptions& damage, const RepairOptions& options,
                           std::vector<RepairEvaluationRow>* rows);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_REPAIR_REPAIR_EVALUATION_H_
