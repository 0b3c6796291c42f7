// Subsampling (Algorithm 5 with the normal check, the per-joint and per-part minimums), mesh mapping
// (eq. 11 in the common rest frame) and the setup's blend mask, on the synthetic cylinder
// character over the demo skeleton.
#include "problems/retarget/retarget_setup.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "problems/retarget/mesh_mapping.h"
#include "problems/retarget/synthetic_skinned_character.h"
#include "problems/retarget/vertex_subsampling.h"

namespace mocapsolve {
namespace {

class RetargetSetupTest : public ::testing::Test {
 protected:
  Skeleton skeleton_ = MakeDemoSkeleton();
  SkinnedMesh mesh_ = MakeCylinderCharacter(skeleton_);
};

TEST_F(RetargetSetupTest, SubsamplingSpreadsAndCoversEveryJoint) {
  Eigen::Matrix3Xd positions, normals;
  BindPoseMesh(mesh_, Eigen::Matrix3d::Identity(), &positions, &normals);
  SubsampleOptions options;
  const std::vector<int> samples = SubsampleVertices(mesh_, positions, normals, options);
  const int nv = mesh_.num_vertices();
  EXPECT_GE(static_cast<int>(samples.size()), nv / options.ratio);
  EXPECT_EQ(std::set<int>(samples.begin(), samples.end()).size(), samples.size()) << "duplicates";
  std::vector<int> per_joint(skeleton_.num_joints(), 0);
  for (int s : samples) ++per_joint[DominantJoint(mesh_, s)];
  for (int j = 0; j < skeleton_.num_joints(); ++j) {
    EXPECT_GE(per_joint[j], options.min_per_joint) << skeleton_.name(j);
  }
  // Farthest-point sampling: the first nv / ratio samples are at least as far apart as
  // a plain every-n-th pick of the same count would be at its closest pair.
  const int count = nv / options.ratio;
  auto min_gap = [&](const std::vector<int>& picks) {
    double gap = 1e300;
    for (size_t a = 0; a < picks.size(); ++a) {
      for (size_t b = a + 1; b < picks.size(); ++b) {
        gap = std::min(gap, (positions.col(picks[a]) - positions.col(picks[b])).norm());
      }
    }
    return gap;
  };
  std::vector<int> fps(samples.begin(), samples.begin() + count), strided;
  for (int k = 0; k < count; ++k) strided.push_back(k * (nv / count));
  EXPECT_GT(min_gap(fps), min_gap(strided));
}

// Per body part: with one whole-mesh sample (ratio = #V) and no per-joint minimum, every
// part with vertices still gets min_per_part samples, each on its own part (RobotExpressive's
// arm parts were left with 0-2 of ~75 tracked vertices).
TEST_F(RetargetSetupTest, EveryPartGetsItsQuota) {
  Eigen::Matrix3Xd positions, normals;
  BindPoseMesh(mesh_, Eigen::Matrix3d::Identity(), &positions, &normals);
  SubsampleOptions options;
  options.ratio = mesh_.num_vertices();
  options.min_per_joint = 0;
  options.min_per_part = 6;
  std::vector<int> parts(mesh_.num_vertices());
  for (int v = 0; v < mesh_.num_vertices(); ++v) parts[v] = DominantJoint(mesh_, v) % 4;
  parts[0] = -1;  // No part.
  const auto counts = [&](const std::vector<int>& samples) {
    std::vector<int> count(4, 0);
    for (int s : samples) {
      if (parts[s] >= 0) ++count[parts[s]];
    }
    return count;
  };
  const std::vector<int> without = counts(SubsampleVertices(mesh_, positions, normals, options));
  EXPECT_LT(*std::min_element(without.begin(), without.end()), options.min_per_part);
  const std::vector<int> samples = SubsampleVertices(mesh_, positions, normals, options, parts);
  EXPECT_EQ(std::set<int>(samples.begin(), samples.end()).size(), samples.size()) << "duplicates";
  for (int count : counts(samples)) EXPECT_GE(count, options.min_per_part);
}

TEST_F(RetargetSetupTest, NormalCheckExcludesVerticesUnlikeTheirNeighbours) {
  Eigen::Matrix3Xd positions, normals;
  BindPoseMesh(mesh_, Eigen::Matrix3d::Identity(), &positions, &normals);
  // Flip the normals of every tenth vertex: none of them may be picked by the sampling
  // proper (the per-joint minimum may still fall back to them, so use min_per_joint 0).
  for (int i = 0; i < normals.cols(); i += 10) normals.col(i) = -normals.col(i);
  SubsampleOptions options;
  options.min_per_joint = 0;
  options.ratio = 16;
  options.first = 1;
  const std::vector<int> samples = SubsampleVertices(mesh_, positions, normals, options);
  ASSERT_FALSE(samples.empty());
  for (int s : samples) EXPECT_NE(s % 10, 0) << "vertex " << s;
  // Without the check they are picked.
  options.normal_threshold = 2.0;
  const std::vector<int> unchecked = SubsampleVertices(mesh_, positions, normals, options);
  EXPECT_TRUE(std::any_of(unchecked.begin(), unchecked.end(), [](int s) { return s % 10 == 0; }));
}

TEST_F(RetargetSetupTest, MappingOntoItselfAndOntoAScaledCopy) {
  const Skeleton scaled_skeleton = ScaleSkeleton(skeleton_, 0.7);
  const SkinnedMesh scaled = MakeCylinderCharacter(scaled_skeleton);
  const CharacterFrame frame = ComputeCharacterFrame(mesh_.rest_positions());
  const CharacterFrame scaled_frame = ComputeCharacterFrame(scaled.rest_positions());
  EXPECT_NEAR(scaled_frame.height / frame.height, 0.7, 1e-12);
  std::vector<int> all;
  for (int i = 0; i < mesh_.num_vertices(); i += 7) all.push_back(i);
  Eigen::Matrix3Xd points(3, all.size());
  for (size_t k = 0; k < all.size(); ++k) points.col(k) = mesh_.rest_positions().col(all[k]);
  const std::vector<int> self = MapToNearestVertices(points, frame, mesh_.rest_positions(), frame);
  const std::vector<int> copy = MapToNearestVertices(points, frame, scaled.rest_positions(), scaled_frame);
  for (size_t k = 0; k < all.size(); ++k) {
    EXPECT_EQ(self[k], all[k]);
    EXPECT_EQ(copy[k], all[k]);  // Same construction, so the same vertex order.
  }
}

TEST_F(RetargetSetupTest, AutomaticBlendMaskTracksEndEffectorsByPosition) {
  RetargetSetup setup;
  ASSERT_TRUE(BuildRetargetSetup(mesh_, skeleton_, mesh_, RetargetSetupOptions(), &setup).ok());
  ASSERT_FALSE(setup.tracked.empty());
  EXPECT_NEAR(setup.scale, 1.0, 1e-12);
  int positions = 0, normals = 0;
  for (const TrackedVertex& t : setup.tracked) {
    EXPECT_EQ(t.source_vertex, t.target_vertex);
    const std::string name = skeleton_.name(DominantJoint(mesh_, t.target_vertex));
    const bool end_effector = name.find("Hand") != std::string::npos ||
                              name.find("Foot") != std::string::npos ||
                              name.find("Toe") != std::string::npos || name == "Head";
    // Cylinder vertices blend at most 50% across a joint, so the dominant joint decides.
    EXPECT_EQ(t.track_position, end_effector) << name;
    (t.track_position ? positions : normals) += 1;
  }
  EXPECT_GT(positions, 0);
  EXPECT_GT(normals, 0);

  RetargetSetupOptions options;
  options.position_joints = {"Hips"};  // Everything below the hips: all positions.
  ASSERT_TRUE(BuildRetargetSetup(mesh_, skeleton_, mesh_, options, &setup).ok());
  for (const TrackedVertex& t : setup.tracked) EXPECT_TRUE(t.track_position);

  options.position_joints = {"NoSuchJoint"};
  const Status status = BuildRetargetSetup(mesh_, skeleton_, mesh_, options, &setup);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("NoSuchJoint"), std::string::npos) << status.message();
}

TEST_F(RetargetSetupTest, GoalsAreTheSourceScaledIntoTheTarget) {
  const Skeleton big_skeleton = ScaleSkeleton(skeleton_, 2.0);
  const SkinnedMesh big = MakeCylinderCharacter(big_skeleton);
  RetargetSetup setup;
  ASSERT_TRUE(BuildRetargetSetup(mesh_, big_skeleton, big, RetargetSetupOptions(), &setup).ok());
  EXPECT_NEAR(setup.scale, 2.0, 1e-12);
  const Motion walk = MakeDemoWalk(skeleton_, 5, 30.0);
  RetargetGoals goals, big_goals;
  ComputeRetargetGoals(setup, skeleton_, mesh_, walk, &goals);
  // The same walk on the big character, tracked onto itself: the same goals.
  RetargetSetup self;
  ASSERT_TRUE(BuildRetargetSetup(big, big_skeleton, big, RetargetSetupOptions(), &self).ok());
  ASSERT_EQ(self.tracked.size(), setup.tracked.size());
  ComputeRetargetGoals(self, big_skeleton, big, ScaleMotion(walk, 2.0), &big_goals);
  EXPECT_NEAR(goals.sigma, big_goals.sigma, 1e-9 * big_goals.sigma);
  for (int f = 0; f < walk.num_frames(); ++f) {
    EXPECT_LT((goals.positions[f] - big_goals.positions[f]).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT((goals.normals[f] - big_goals.normals[f]).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// Frame by frame (a long clip's goals are not held): the same columns and the same sigma,
// bit for bit, as the whole clip's.
TEST_F(RetargetSetupTest, GoalsFrameByFrameEqualTheWholeClips) {
  const Skeleton big_skeleton = ScaleSkeleton(skeleton_, 1.5);
  const SkinnedMesh big = MakeCylinderCharacter(big_skeleton);
  RetargetSetup setup;
  ASSERT_TRUE(BuildRetargetSetup(mesh_, big_skeleton, big, RetargetSetupOptions(), &setup).ok());
  const Motion walk = MakeDemoWalk(skeleton_, 12, 30.0);
  RetargetGoals goals;
  ComputeRetargetGoals(setup, skeleton_, mesh_, walk, &goals);
  RetargetGoalFrames frames(setup, skeleton_, mesh_);
  double sigma = 0.0;
  ASSERT_TRUE(frames.Sigma(walk, &sigma));
  EXPECT_EQ(sigma, goals.sigma);
  Eigen::Matrix3Xd positions, normals, positions_only;
  for (int f = walk.num_frames() - 1; f >= 0; --f) {  // Any order: nothing carried over.
    frames.Frame(walk.frames[f], &positions, &normals);
    EXPECT_TRUE(positions == goals.positions[f]) << f;
    EXPECT_TRUE(normals == goals.normals[f]) << f;
    frames.Frame(walk.frames[f], &positions_only, nullptr);
    EXPECT_TRUE(positions_only == goals.positions[f]) << f;
  }
  Motion broken = walk;
  broken.frames[3].translations[0].x() = std::nan("");
  EXPECT_FALSE(frames.Sigma(broken, &sigma));
}

}  // namespace
}  // namespace mocapsolve
