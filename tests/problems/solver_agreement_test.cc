// Both per-frame solvers end every frame at the same cost (problems/marker_solve/
// solver_agreement.h), here on a take that turns a two-axis joint's second angle past a
// quarter turn: a solve that crossed it used to freeze there (the manifold read the pose
// as another point of its set and rejected every later step), in whichever solver
// happened to step across first.
#include "problems/marker_solve/solver_agreement.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {
namespace {

// The demo skeleton with the right forearm on two axes (x then z, as an ASF "dof rx rz").
Skeleton TwoAxisForearm(int* forearm) {
  const Skeleton demo = MakeDemoSkeleton();
  std::vector<JointSpec> joints;
  for (int j = 0; j < demo.num_joints(); ++j) {
    joints.push_back(demo.joint(j));
    if (joints.back().name == "RightForeArm") {
      joints.back().rotation_axes = std::vector<int>{0, 2};
      *forearm = j;
    }
  }
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(joints, demo.end_sites(), demo.unit(), &skeleton).ok());
  return skeleton;
}

TEST(SolverAgreement, TwoAxisJointPastAQuarterTurnIsFollowedByBothSolvers) {
  int forearm = -1;
  const Skeleton skeleton = TwoAxisForearm(&forearm);
  ASSERT_GE(forearm, 0);
  std::mt19937 rng(7);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion walk = MakeDemoWalk(MakeDemoSkeleton(), 30, 30.0);
  DofQuaternionManifold two({0, 2});
  std::vector<std::vector<Eigen::Vector3d>> observed;
  FkData fk(skeleton);
  std::normal_distribution<double> noise(0.0, 0.05);  // 0.5 mm: costs well above round-off.
  for (int f = 0; f < walk.num_frames(); ++f) {
    Pose pose = walk.frames[f];
    const double angles[2] = {0.3, 1.2 + 0.04 * f};  // The second angle 1.2 -> 2.36 rad.
    Eigen::Quaterniond q;
    two.Compose(angles, q.coeffs().data());
    pose.rotations[forearm] = q;
    ForwardKinematics(skeleton, pose, &fk);
    observed.emplace_back();
    for (int m = 0; m < markers.num_markers(); ++m) {
      observed.back().push_back(markers.Position(m, fk) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
  }
  MarkerSolveOptions options;
  options.ceres = DefaultFrameCeresOptions();
  options.ceres.function_tolerance = options.dls.function_tolerance = 1e-6;
  options.prior_rotation_weight = 0.05;
  SolverAgreementReport report;
  ASSERT_TRUE(CompareSolvers(skeleton, markers, observed, options, RestPose(skeleton), 0.01, 5, &report).ok());
  EXPECT_EQ(report.frames_compared, walk.num_frames());
  EXPECT_EQ(report.frames_within, walk.num_frames());
  EXPECT_TRUE(report.worst.empty());
  for (int f = 0; f < walk.num_frames(); ++f) {
    // The markers are matched to their noise (0.5 mm a coordinate, about 0.9 mm RMS);
    // a frozen forearm would be centimetres off within a few frames.
    EXPECT_LT(report.dls.frame_rms[f], 0.15) << f;
    EXPECT_LT(report.ceres.frame_rms[f], 0.15) << f;
  }
}

TEST(SolverAgreement, ListsDifferingFramesWorstFirstAndRejectsANegativeTolerance) {
  int forearm = -1;
  const Skeleton skeleton = TwoAxisForearm(&forearm);
  std::mt19937 rng(8);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion walk = MakeDemoWalk(skeleton, 6, 30.0);
  std::vector<std::vector<Eigen::Vector3d>> observed;
  FkData fk(skeleton);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (const Pose& pose : walk.frames) {
    ForwardKinematics(skeleton, pose, &fk);
    observed.emplace_back();
    for (int m = 0; m < markers.num_markers(); ++m) {
      observed.back().push_back(markers.Position(m, fk) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
  }
  MarkerSolveOptions options;
  options.ceres = DefaultFrameCeresOptions();
  SolverAgreementReport report;
  // Tolerance 0: every frame whose costs differ at all is listed, largest first.
  ASSERT_TRUE(CompareSolvers(skeleton, markers, observed, options, RestPose(skeleton), 0.0, 3, &report).ok());
  EXPECT_LE(report.worst.size(), 3u);
  for (size_t i = 1; i < report.worst.size(); ++i) EXPECT_GE(report.worst[i - 1].relative, report.worst[i].relative);
  for (const SolverAgreementFrame& frame : report.worst) EXPECT_GT(frame.relative, 0.0);
  EXPECT_FALSE(CompareSolvers(skeleton, markers, observed, options, RestPose(skeleton), -1.0, 3, &report).ok());
}

}  // namespace
}  // namespace mocapsolve
