// Shared fixtures of the marker-repair tests: noise-free markers on the demo character and
// the repair options of `mocapsolve repair`, in the demo's centimetres.
#ifndef MOCAPSOLVE_TESTS_PROBLEMS_REPAIR_TEST_SUPPORT_H_
#define MOCAPSOLVE_TESTS_PROBLEMS_REPAIR_TEST_SUPPORT_H_

#include <cstdint>
#include <vector>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_repair/marker_repair.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace testing {

struct DemoTake {
  Skeleton skeleton;
  Motion truth;
  MarkerSet markers;
  std::vector<std::vector<Eigen::Vector3d>> clean;  // [frame][marker], cm.
};

// The demo walk with 3 synthetic markers per bone (marker set seed `set_seed`).
inline DemoTake MakeDemoTake(int frames, double frame_rate, uint32_t set_seed) {
  DemoTake take;
  take.skeleton = MakeDemoSkeleton();
  take.truth = MakeDemoWalk(take.skeleton, frames, frame_rate);
  take.markers = MakeSyntheticMarkerSet(take.skeleton, 3, set_seed);
  FkData fk(take.skeleton);
  for (const Pose& pose : take.truth.frames) {
    ForwardKinematics(take.skeleton, pose, &fk);
    take.clean.emplace_back();
    for (int m = 0; m < take.markers.num_markers(); ++m) take.clean.back().push_back(take.markers.Position(m, fk));
  }
  return take;
}

// `mocapsolve repair`'s defaults in cm: DLS naive solve with a 20 mm/rad prior, a Cauchy
// reference bending at 1 cm (the tracker stopping at a relative cost change of 1e-4),
// thesis thresholds (10 cm, 30 degrees), outliers past 4 cm.
inline RepairOptions DemoRepairOptions(ReferenceKind reference_kind) {
  RepairOptions options;
  options.naive.solver = SolverKind::kDls;
  options.naive.prior_rotation_weight = 2.0;
  options.reference_kind = reference_kind;
  options.reference.ceres = DefaultClipCeresOptions();
  options.reference.loss = "cauchy";
  options.reference.loss_scale = 1.0;
  options.tracker = options.naive;
  options.tracker.loss = "cauchy";
  options.tracker.loss_scale = 1.0;
  options.tracker.dls.function_tolerance = 1e-4;
  options.dp_max = 10.0;
  options.dr_max_rad = DegToRad(30.0);
  options.outlier_distance = 4.0;
  options.velocity_clamp = 0.25;
  return options;
}

}  // namespace testing
}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TESTS_PROBLEMS_REPAIR_TEST_SUPPORT_H_
