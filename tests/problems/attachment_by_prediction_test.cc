// Attachment by prediction: a marker rigid on a foot that its toe joint holds nearly as
// well goes to the foot; one that the toe clearly turns stays on the toe; a marker that
// moves rigidly with the foot's markers but was put on a toe that holds it far worse is a
// candidate by co-rigidity and goes to the foot. A marker over the knee that both bones
// pull (a 50/50 blend) is offered the blend and takes it; one that rides the thigh alone,
// offered the same blend, keeps the thigh.
#include "problems/marker_solve/attachment_by_prediction.h"

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/calibration.h"
#include "problems/marker_solve/rigid_marker_clusters.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

// Every marker of `set`, to change some and make a set again.
std::vector<MarkerSpec> SpecsOf(const MarkerSet& set) {
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < set.num_markers(); ++m) specs.push_back(set.marker(m));
  return specs;
}

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
  std::vector<double> toe_and_foot_rms;                // MT5's rms about that fit on each.
};

// MT5 rides `joint` at `offset`; the fixture's observations of `motion`.
Fixture MakeFixture(const Skeleton& skeleton, const Motion& motion, int joint, const Eigen::Vector3d& offset,
                    double noise_cm = 0.3) {
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
  std::normal_distribution<double> noise(0.0, noise_cm);
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
    double sum = 0.0;
    for (const Eigen::Vector3d& l : local[k]) sum += (l - fixture.toe_and_foot.back().offset).squaredNorm();
    fixture.toe_and_foot_rms.push_back(std::sqrt(sum / local[k].size()));
  }
  return fixture;
}

// MT5 attached to the toe (as auto attach would by a hair), the foot its alternative.
int DecidedJoint(const Skeleton& skeleton, const Fixture& fixture, std::vector<AttachmentMove>* moves) {
  std::vector<MarkerSpec> specs = SpecsOf(fixture.truth);
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

// The rigid clusters of the fixture's markers (their observations as a take, cm).
std::vector<std::vector<int>> Clusters(const Fixture& fixture) {
  std::vector<std::string> labels;
  for (int m = 0; m < fixture.truth.num_markers(); ++m) labels.push_back(fixture.truth.label(m));
  MarkerTrajectories take(labels, static_cast<int>(fixture.observed.size()));
  for (int f = 0; f < take.num_frames(); ++f) {
    for (int m = 0; m < take.num_markers(); ++m) take.SetSample(f, m, fixture.observed[f][m]);
  }
  std::vector<int> all(take.num_markers());
  for (int m = 0; m < take.num_markers(); ++m) all[m] = m;
  const RigidClusterOptions options;
  return ClusterRigidMarkers(ComputePairwiseSpread(take, all, 0.01, options), options);
}

TEST(AttachmentByPrediction, RigidClusterCandidateIsTheJointOfMostOfTheOthers) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::vector<MarkerSpec> specs;
  const int foot = skeleton.FindJoint("LeftFoot"), toe = skeleton.FindJoint("LeftToe");
  for (const auto& [label, joint] : std::vector<std::pair<std::string, int>>{
           {"A", toe}, {"B", foot}, {"C", foot}, {"D", toe}, {"E", toe}, {"F", foot}, {"G", foot}}) {
    specs.push_back({label, {{joint, 1.0, Eigen::Vector3d::Zero()}}});
  }
  MarkerSet set;
  ASSERT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  // {A, B, C}: two of three on the foot, A's candidate. {D, E}: too few to tell.
  // {F, G}: nothing to move.
  const std::vector<int> candidates = RigidClusterCandidates(set, {{0, 1, 2}, {3, 4}, {5, 6}});
  EXPECT_EQ(candidates, (std::vector<int>{foot, -1, -1, -1, -1, -1, -1}));
  // {D, E, F, G}: two and two, no joint holds more than half.
  EXPECT_EQ(RigidClusterCandidates(set, {{3, 4, 5, 6}}), std::vector<int>(7, -1));
  // {B, D, E, F, G}: three of five on the foot, D and E its candidates.
  EXPECT_EQ(RigidClusterCandidates(set, {{1, 3, 4, 5, 6}}), (std::vector<int>{-1, -1, -1, foot, foot, -1, -1}));
}

// Every marker of `set` placed on `motion` with 0.2 (skeleton units) of Gaussian noise per
// coordinate, seed 3.
std::vector<std::vector<Eigen::Vector3d>> NoisyObservations(const Skeleton& skeleton, const MarkerSet& set,
                                                            const Motion& motion) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.2);
  FkData fk(skeleton);
  std::vector<std::vector<Eigen::Vector3d>> observed;
  for (const Pose& pose : motion.frames) {
    ForwardKinematics(skeleton, pose, &fk);
    std::vector<Eigen::Vector3d> frame;
    for (int m = 0; m < set.num_markers(); ++m) {
      frame.push_back(set.Position(m, fk) + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
    observed.push_back(frame);
  }
  return observed;
}

TEST(AttachmentByPrediction, AMarkerRigidWithTheFootButPutOnTheToeGoesToTheFoot) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int toe = skeleton.FindJoint("LeftToe");
  const int foot = skeleton.parent(toe);
  // On the foot beside the toe joint, the toe turning 0.4 rad; 1 mm of skin noise.
  const Eigen::Vector3d beside_toe = skeleton.offset(toe) + Eigen::Vector3d(3.0, 0.0, 0.0);
  const Fixture fixture = MakeFixture(skeleton, Walk(skeleton, toe, 0.4), foot, beside_toe, 0.1);
  // The toe holds it far worse than the foot: no near tie for PredictionCandidates' 15 %.
  EXPECT_GT(fixture.toe_and_foot_rms[0], 1.15 * fixture.toe_and_foot_rms[1]);
  std::vector<MarkerSpec> specs = SpecsOf(fixture.truth);
  specs.back().attachments = {fixture.toe_and_foot[0]};
  MarkerSet set;
  ASSERT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  const std::vector<int> candidates = RigidClusterCandidates(set, Clusters(fixture));
  const int mt5 = set.num_markers() - 1;
  ASSERT_EQ(candidates[mt5], foot);
  std::vector<MarkerAttachment> alternative(set.num_markers(), MarkerAttachment());
  alternative[mt5] = fixture.toe_and_foot[1];
  std::vector<AttachmentMove> moves;
  ASSERT_TRUE(ChooseAttachmentsByPrediction(skeleton, fixture.observed, alternative, MarkerSolveOptions(), {}, &set,
                                            &moves)
                  .ok());
  EXPECT_EQ(set.marker(mt5).attachments[0].joint, foot);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_LT(moves[0].to_score, moves[0].from_score);
}

// The fixture's observations as a take (skeleton units).
MarkerTrajectories AsTake(const MarkerSet& truth, const std::vector<std::vector<Eigen::Vector3d>>& observed) {
  std::vector<std::string> labels;
  for (int m = 0; m < truth.num_markers(); ++m) labels.push_back(truth.label(m));
  MarkerTrajectories take(labels, static_cast<int>(observed.size()));
  for (int f = 0; f < take.num_frames(); ++f) {
    for (int m = 0; m < take.num_markers(); ++m) take.SetSample(f, m, observed[f][m]);
  }
  return take;
}

// The offsets of `attachments` for the fixture's marker "PAT" by least squares
// (calibration.h, fixed attachments) on the true motion.
AttachmentChoice FitPat(const Skeleton& skeleton, const Motion& motion, const MarkerTrajectories& take,
                        const AttachmentChoice& attachments) {
  MarkerSet one;
  EXPECT_TRUE(MarkerSet::Create(skeleton, {{"PAT", attachments}}, &one).ok());
  CalibrationResult fit;
  EXPECT_TRUE(CalibrateMarkers(skeleton, motion, take, CalibrationOptions(), &one, &fit).ok());
  EXPECT_EQ(fit.marker_set.num_markers(), 1);
  return fit.marker_set.marker(0).attachments;
}

// "PAT", 6 cm in front of the left knee, rides `truth` (the thigh, or both bones 50/50);
// given on the thigh with its blend over the knee as the alternative: the attachments
// the prediction keeps.
AttachmentChoice DecidedPatella(const AttachmentChoice& truth, std::vector<AttachmentMove>* moves) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), knee = skeleton.FindJoint("LeftLeg");
  const Motion motion = Walk(skeleton, knee, 0.1);
  std::vector<MarkerSpec> specs = SpecsOf(MakeSyntheticMarkerSet(skeleton, 3, 7));
  specs.push_back({"PAT", truth});
  MarkerSet set;
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  const std::vector<std::vector<Eigen::Vector3d>> observed = NoisyObservations(skeleton, set, motion);
  const MarkerTrajectories take = AsTake(set, observed);
  specs.back().attachments = FitPat(skeleton, motion, take, {{thigh, 1.0, Eigen::Vector3d::Zero()}});
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  const int pat = set.num_markers() - 1;
  // The blend candidate is the knee's, found from the marker's offset alone.
  const std::vector<std::pair<int, int>> hinges = HingeBlendCandidates(skeleton, set, 10.0, 0.25, 3);
  EXPECT_EQ(hinges[pat], std::make_pair(thigh, knee));
  std::vector<std::vector<AttachmentChoice>> alternatives(set.num_markers());
  alternatives[pat] = {FitPat(skeleton, motion, take,
                              {{thigh, 0.5, Eigen::Vector3d::Zero()}, {knee, 0.5, Eigen::Vector3d::Zero()}})};
  EXPECT_TRUE(ChooseAmongAttachments(skeleton, observed, alternatives, MarkerSolveOptions(), {}, &set, moves).ok());
  return set.marker(pat).attachments;
}

TEST(AttachmentByPrediction, AMarkerBothBonesPullTakesTheBlendOverTheKnee) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), knee = skeleton.FindJoint("LeftLeg");
  const Eigen::Vector3d front(0.0, 0.0, 6.0);
  std::vector<AttachmentMove> moves;
  const AttachmentChoice kept =
      DecidedPatella({{thigh, 0.5, skeleton.offset(knee) + front}, {knee, 0.5, front}}, &moves);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].joint, thigh);
  EXPECT_EQ(kept[1].joint, knee);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_TRUE(moves[0].moved);
  EXPECT_LT(moves[0].to_score, 0.9 * moves[0].from_score);
}

TEST(AttachmentByPrediction, AMarkerOnTheThighKeepsTheThighOverTheBlend) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), knee = skeleton.FindJoint("LeftLeg");
  std::vector<AttachmentMove> moves;
  const AttachmentChoice kept =
      DecidedPatella({{thigh, 1.0, skeleton.offset(knee) + Eigen::Vector3d(0.0, 4.0, 6.0)}}, &moves);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0].joint, thigh);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_FALSE(moves[0].moved);
}

TEST(AttachmentByPrediction, HingeBlendCandidatesAreTheNearestJointWithinTheRadius) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int hips = skeleton.FindJoint("Hips"), thigh = skeleton.FindJoint("LeftUpLeg");
  const int knee = skeleton.FindJoint("LeftLeg"), foot = skeleton.FindJoint("LeftFoot");
  MarkerSet set;
  ASSERT_TRUE(MarkerSet::Create(skeleton,
                                {{"ABOVE_KNEE", {{thigh, 1.0, skeleton.offset(knee) + Eigen::Vector3d(0, 3, 5)}}},
                                 {"BELOW_KNEE", {{knee, 1.0, Eigen::Vector3d(0, -3, 5)}}},
                                 {"MID_THIGH", {{thigh, 1.0, Eigen::Vector3d(0, -21, 6)}}},
                                 {"ANKLE", {{knee, 1.0, skeleton.offset(foot) + Eigen::Vector3d(4, 0, 0)}}},
                                 {"ROOT", {{hips, 1.0, Eigen::Vector3d(0, 0, 5)}}},
                                 {"BLENDED", {{thigh, 0.5, Eigen::Vector3d::Zero()}, {knee, 0.5, Eigen::Vector3d::Zero()}}}},
                                &set)
                  .ok());
  const std::vector<std::pair<int, int>> hinges = HingeBlendCandidates(skeleton, set, 10.0, 0.25, 3);
  const std::pair<int, int> none(-1, -1);
  EXPECT_EQ(hinges[0], std::make_pair(thigh, knee));
  EXPECT_EQ(hinges[1], std::make_pair(thigh, knee));
  EXPECT_EQ(hinges[2], none);  // 21 cm from either end of the thigh.
  EXPECT_EQ(hinges[3], std::make_pair(knee, foot));
  EXPECT_EQ(hinges[4], none);  // The root has no parent; its children's joints are > 10 cm away.
  EXPECT_EQ(hinges[5], none);  // Already a blend.
  const std::vector<std::pair<int, int>> all_none(6, none);
  EXPECT_EQ(HingeBlendCandidates(skeleton, set, 0.0, 0.25, 3), all_none);
}

TEST(AttachmentByPrediction, AMidBoneWandIsNotOfferedTheBlend) {
  // Within a 15 cm skin radius of the knee but 12 cm along the thigh (42 cm) or the shin
  // (41 cm) from it, beyond a quarter of either: wands riding their bone, no blend. The
  // patella over the knee keeps its candidate.
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), knee = skeleton.FindJoint("LeftLeg");
  MarkerSet set;
  ASSERT_TRUE(MarkerSet::Create(skeleton,
                                {{"THIGH_WAND", {{thigh, 1.0, skeleton.offset(knee) + Eigen::Vector3d(0, 12, 6)}}},
                                 {"SHIN_WAND", {{knee, 1.0, Eigen::Vector3d(0, -12, 6)}}},
                                 {"PATELLA", {{thigh, 1.0, skeleton.offset(knee) + Eigen::Vector3d(0, 3, 5)}}}},
                                &set)
                  .ok());
  const std::pair<int, int> none(-1, -1);
  const std::vector<std::pair<int, int>> hinges = HingeBlendCandidates(skeleton, set, 15.0, 0.25, 3);
  EXPECT_EQ(hinges[0], none);
  EXPECT_EQ(hinges[1], none);
  EXPECT_EQ(hinges[2], std::make_pair(thigh, knee));
  // With no limit along the bone (h36i), both wands were offered the knee's blend.
  const std::vector<std::pair<int, int>> unlimited = HingeBlendCandidates(skeleton, set, 15.0, 1.0, 3);
  EXPECT_EQ(unlimited[0], std::make_pair(thigh, knee));
  EXPECT_EQ(unlimited[1], std::make_pair(thigh, knee));
}

TEST(AttachmentByPrediction, OnlyAHingeOfAtMostMaxDofsIsOffered) {
  // The demo's knee rotates about 3 axes; made a one-axis hinge it is offered with max_dofs 1,
  // the ball joint is not.
  const Skeleton ball = MakeDemoSkeleton();
  const int thigh = ball.FindJoint("LeftUpLeg"), knee = ball.FindJoint("LeftLeg");
  std::vector<JointSpec> joints;
  for (int j = 0; j < ball.num_joints(); ++j) joints.push_back(ball.joint(j));
  joints[knee].rotation_axes = std::vector<int>{0};
  joints[knee].rotation_limits.clear();
  Skeleton hinge;
  ASSERT_TRUE(Skeleton::Create(joints, ball.end_sites(), ball.unit(), &hinge).ok());
  ASSERT_EQ(hinge.num_rotation_dofs(knee), 1);
  ASSERT_GT(ball.num_rotation_dofs(knee), 1);
  const std::vector<MarkerSpec> patella = {
      {"PATELLA", {{thigh, 1.0, ball.offset(knee) + Eigen::Vector3d(0, 3, 5)}}}};
  MarkerSet on_ball, on_hinge;
  ASSERT_TRUE(MarkerSet::Create(ball, patella, &on_ball).ok());
  ASSERT_TRUE(MarkerSet::Create(hinge, patella, &on_hinge).ok());
  EXPECT_EQ(HingeBlendCandidates(hinge, on_hinge, 10.0, 0.25, 1)[0], std::make_pair(thigh, knee));
  EXPECT_EQ(HingeBlendCandidates(ball, on_ball, 10.0, 0.25, 1)[0], std::make_pair(-1, -1));
  EXPECT_EQ(HingeBlendCandidates(ball, on_ball, 10.0, 0.25, 3)[0], std::make_pair(thigh, knee));
}

TEST(AttachmentByPrediction, AHingeThatHoldsStillInTheFitFramesIsNotOffered) {
  // The patella's knee candidate survives a walk in which the knee bends; held at one
  // rotation (the rest of the body walking), or bent by less than min_bend, it is dropped:
  // the blend's offsets are fitted on those frames and a still knee cannot tell them apart.
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), knee = skeleton.FindJoint("LeftLeg");
  MarkerSet set;
  ASSERT_TRUE(MarkerSet::Create(skeleton, {{"PATELLA", {{thigh, 1.0, skeleton.offset(knee) + Eigen::Vector3d(0, 3, 5)}}}},
                                &set)
                  .ok());
  const std::vector<std::pair<int, int>> offered = HingeBlendCandidates(skeleton, set, 10.0, 0.25, 3);
  ASSERT_EQ(offered[0], std::make_pair(thigh, knee));
  const double min_bend = AttachmentByPredictionOptions().hinge_min_bend;
  const Motion walk = MakeDemoWalk(skeleton, 120, 60.0);
  ASSERT_GT(JointBendRange(walk, knee, 240), min_bend);
  std::vector<std::pair<int, int>> hinges = offered;
  DropHingesThatHoldStill(walk, min_bend, 240, &hinges);
  EXPECT_EQ(hinges[0], std::make_pair(thigh, knee));
  // The knee bent linearly from 0 to 0.2 rad (11.5 degrees) about one axis: that range, below 15.
  Motion still = walk;
  for (int f = 0; f < still.num_frames(); ++f) {
    still.frames[f].rotations[knee] = ExpMap(Eigen::Vector3d(0.2 * f / (still.num_frames() - 1), 0.0, 0.0));
  }
  EXPECT_NEAR(JointBendRange(still, knee, 240), 0.2, 1e-9);
  EXPECT_NEAR(JointBendRange(still, knee, 7), 0.2 * 108 / 119, 1e-9);  // Frames 0, 18, ..., 108.
  hinges = offered;
  DropHingesThatHoldStill(still, min_bend, 240, &hinges);
  EXPECT_EQ(hinges[0], std::make_pair(-1, -1));
  for (Pose& pose : still.frames) pose.rotations[knee] = walk.frames[0].rotations[knee];
  EXPECT_NEAR(JointBendRange(still, knee, 240), 0.0, 1e-9);
}

// ChooseLimbBlends on the left leg: "PAT" rides the knee 50/50 and "LAT", 6 cm to the side
// of it, the thigh alone; both are given on the thigh with the knee's blend as candidate
// (offsets by least squares on the true motion). limb_rise: the options'.
std::vector<AttachmentChoice> DecidedLimb(double limb_rise, std::vector<AttachmentMove>* moves) {
  const Skeleton skeleton = MakeDemoSkeleton();
  const int thigh = skeleton.FindJoint("LeftUpLeg"), knee = skeleton.FindJoint("LeftLeg");
  const Motion motion = Walk(skeleton, knee, 0.1);
  std::vector<MarkerSpec> specs = SpecsOf(MakeSyntheticMarkerSet(skeleton, 3, 7));
  const Eigen::Vector3d front(0.0, 0.0, 6.0), side(6.0, 3.0, 0.0);
  specs.push_back({"PAT", {{thigh, 0.5, skeleton.offset(knee) + front}, {knee, 0.5, front}}});
  specs.push_back({"LAT", {{thigh, 1.0, skeleton.offset(knee) + side}}});
  MarkerSet set;
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  const std::vector<std::vector<Eigen::Vector3d>> observed = NoisyObservations(skeleton, set, motion);
  const MarkerTrajectories take = AsTake(set, observed);
  const AttachmentChoice on_thigh = {{thigh, 1.0, Eigen::Vector3d::Zero()}};
  const AttachmentChoice blend = {{thigh, 0.5, Eigen::Vector3d::Zero()}, {knee, 0.5, Eigen::Vector3d::Zero()}};
  const int pat = set.num_markers() - 2, lat = set.num_markers() - 1;
  std::vector<AttachmentChoice> blends(set.num_markers());
  for (int m : {pat, lat}) {
    MarkerTrajectories own({"PAT"}, take.num_frames());  // FitPat's label.
    for (int f = 0; f < take.num_frames(); ++f) own.SetSample(f, 0, observed[f][m]);
    specs[m].attachments = FitPat(skeleton, motion, own, on_thigh);
    blends[m] = FitPat(skeleton, motion, own, blend);
  }
  EXPECT_TRUE(MarkerSet::Create(skeleton, specs, &set).ok());
  AttachmentByPredictionOptions options;
  options.limb_rise = limb_rise;
  EXPECT_TRUE(ChooseLimbBlends(skeleton, observed, blends, MarkerSolveOptions(), options, &set, moves).ok());
  return {set.marker(pat).attachments, set.marker(lat).attachments};
}

TEST(AttachmentByPrediction, ALimbsBlendsAreDecidedTogether) {
  // One limb (the left leg, from the hip down), two candidates: the patella that both bones
  // pull takes the blend, the marker on the thigh keeps the thigh, scored on every marker
  // of the leg.
  std::vector<AttachmentMove> moves;
  const std::vector<AttachmentChoice> kept = DecidedLimb(0.5, &moves);
  EXPECT_EQ(kept[0].size(), 2u);
  EXPECT_EQ(kept[1].size(), 1u);
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_TRUE(moves[0].moved);
  EXPECT_FALSE(moves[1].moved);
  EXPECT_EQ(moves[0].from_score, moves[1].from_score);  // One limb, one score without blends.
  EXPECT_LT(moves[0].to_score, moves[0].from_score);
  // A blend that raises any marker of the leg at all (limb_rise 0: the thigh's and the
  // shin's synthetic markers move by noise) is refused, however it helps the limb's median.
  const std::vector<AttachmentChoice> strict = DecidedLimb(0.0, &moves);
  EXPECT_EQ(strict[0].size(), 1u);
  EXPECT_EQ(strict[1].size(), 1u);
}

}  // namespace
}  // namespace mocapsolve
