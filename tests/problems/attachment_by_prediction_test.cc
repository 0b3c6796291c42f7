// Attachment by prediction: a marker rigid on a foot that its toe joint holds nearly as
// well goes to the foot; one that the toe clearly turns stays on the toe.
#include "problems/marker_solve/attachment_by_prediction.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

// The demo walk with every joint jittered (0.1 rad), the toe by `toe_turn` rad only.
Motion Walk(const Skeleton& skeleton, int toe, double toe_turn) {
  Motion motion = MakeDemoWalk(skeleton, 120, 60.0);
  std::mt19937 rng(5);
  std::normal_distribution<double> angle(0.0, 1.0);
  for (Pose& pose : motion.frames) {
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const double s = j == toe ? toe_turn : 0.1;
      pose.rotations[j] = (pose.rotations[j] * ExpMap(s * Eigen::Vector3d(angle(rng), angle(rng), angle(rng)))).normalized();
    }
  }
  return motion;
}

struct Fixture {
  MarkerSet truth;        // Three synthetic markers per bone (none on the toe) and "MT5".
  std::vector<std::vector<Eigen::Vector3d>> observed;  // With 0.3 cm of skin noise.
  std::vector<MarkerAttachment> toe_and_foot;          // MT5's least-squares fit on each.
};

// MT5 rides `joint` at `offset`; the fixture's observations of `motion`.
Fixture MakeFixture(const Skeleton& skeleton, const Motion& motion, int joint, const Eigen::Vector3d& offset) {
  const int toe = skeleton.FindJoint("LeftToe");
  const MarkerSet synthetic = MakeSyntheticMarkerSet(skeleton, 3, 7);
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < synthetic.num_markers(); ++m) {
    if (synthetic.marker(m).attachments[0].joint != toe) specs.push_back(synthetic.marker(m));
  }
  specs.push_back({"MT5", {{joint, 1.0, offset}}});
  Fixture fixture;
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &fixture.truth).ok());
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.3);
  FkData fk(skeleton);
  const int mt5 = fixture.truth.num_markers() - 1;
  std::vector<std::vector<Eigen::Vector3d>> local(2);
  for (const Pose& pose : motion.frames) {
    ForwardKinematics(skeleton, pose, &fk);
    std::vector<Eigen::Vector3d> frame;
    for (int m = 0; m < fixture.truth.num_markers(); ++m) {
      frame.push_back(fixture.truth.Position(m, fk) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
    for (int k = 0; k < 2; ++k) {
      const int j = k == 0 ? toe : skeleton.parent(toe);
      local[k].push_back(fk.world_rotations[j].conjugate() * (frame[mt5] - fk.world_positions[j]));
    }
    fixture.observed.push_back(frame);
  }
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& l : local[k]) mean += l;
    fixture.toe_and_foot.push_back({k == 0 ? toe : skeleton.parent(toe), 1.0, mean / local[k].size()});
  }
  return fixture;
}

// MT5 attached to the toe (as auto attach would by a hair), the foot its alternative.
int DecidedJoint(const Skeleton& skeleton, const Fixture& fixture, std::vector<AttachmentMove>* moves) {
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < fixture.truth.num_markers(); ++m) specs.push_back(fixture.truth.marker(m));
  specs.back().attachments = {fixture.toe_and_foot[0]};
  MarkerSet set;
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  std::vector<MarkerAttachment> alternative(set.num_markers(), MarkerAttachment());
  alternative.back() = fixture.toe_and_foot[1];
  EXPECT_TRUE(ChooseAttachmentsByPrediction(skeleton, fixture.observed, alternative, MarkerSolveOptions(), {}, &set, moves)
                  .ok());
  return set.marker(set.num_markers() - 1).attachments[0].joint;
}

TEST(AttachmentByPrediction, ARigidFootKeepsItsMarkerThatTheToeHoldsNearlyAsWell) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int toe = skeleton.FindJoint("LeftToe");
  const int foot = skeleton.parent(toe);
  // On the foot, 3 cm beside the toe joint; the toe barely turns (0.02 rad).
  const Eigen::Vector3d beside_toe = skeleton.offset(toe) + Eigen::Vector3d(3.0, 0.0, 0.0);
  const Fixture fixture = MakeFixture(skeleton, Walk(skeleton, toe, 0.02), foot, beside_toe);
  std::vector<AttachmentMove> moves;
  EXPECT_EQ(DecidedJoint(skeleton, fixture, &moves), foot);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_TRUE(moves[0].moved);
  EXPECT_EQ(moves[0].from, toe);
  EXPECT_LT(moves[0].to_score, moves[0].from_score);
}

TEST(AttachmentByPrediction, AMarkerTheToeTurnsStaysOnTheToe) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int toe = skeleton.FindJoint("LeftToe");
  const Fixture fixture = MakeFixture(skeleton, Walk(skeleton, toe, 0.4), toe, Eigen::Vector3d(3.0, 0.0, 4.0));
  std::vector<AttachmentMove> moves;
  EXPECT_EQ(DecidedJoint(skeleton, fixture, &moves), toe);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_FALSE(moves[0].moved);
}

TEST(AttachmentByPrediction, NoCandidateNoChange) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int toe = skeleton.FindJoint("LeftToe");
  const Fixture fixture = MakeFixture(skeleton, Walk(skeleton, toe, 0.02), toe, Eigen::Vector3d(3.0, 0.0, 0.0));
  MarkerSet set = fixture.truth;
  std::vector<AttachmentMove> moves;
  ASSERT_TRUE(ChooseAttachmentsByPrediction(skeleton, fixture.observed,
                                            std::vector<MarkerAttachment>(set.num_markers(), MarkerAttachment()),
                                            MarkerSolveOptions(), {}, &set, &moves)
                  .ok());
  EXPECT_TRUE(moves.empty());
  EXPECT_EQ(set.marker(set.num_markers() - 1).attachments[0].joint, toe);
  std::vector<MarkerAttachment> wrong_size(1);
  EXPECT_FALSE(ChooseAttachmentsByPrediction(skeleton, fixture.observed, wrong_size, MarkerSolveOptions(), {}, &set,
                                             nullptr)
                   .ok());
}

}  // namespace
}  // namespace mocapsolve
