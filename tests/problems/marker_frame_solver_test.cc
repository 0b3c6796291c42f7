// Per-frame marker solving on noise-free synthetic markers (3 per joint) from the demo
// walk: both solvers recover the pose, and agree with each other.
#include "problems/marker_solve/marker_frame_solver.h"

#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/sequence_solver.h"
#include "problems/marker_solve/synthetic_marker_set.h"
#include "problems/marker_solve/twist_observability.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

std::vector<Eigen::Vector3d> Observe(const Skeleton& skeleton, const MarkerSet& markers, const Pose& pose) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  std::vector<Eigen::Vector3d> observed;
  for (int m = 0; m < markers.num_markers(); ++m) observed.push_back(markers.Position(m, fk));
  return observed;
}

class MarkerFrameSolverTest : public ::testing::TestWithParam<SolverKind> {};

// The demo body with 3 markers a bone, its walk, the left shoulder and a mean pose (the
// walk's frame 2): the arm of the hidden-joint and twist tests.
struct ShoulderFixture {
  Skeleton skeleton = MakeDemoSkeleton();
  MarkerSet markers;
  Motion walk;
  int shoulder = skeleton.FindJoint("LeftShoulder");
  QuaternionVector mean_pose;
  ShoulderFixture() {
    std::mt19937 rng(7);
    markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
    walk = MakeDemoWalk(skeleton, 3, 30.0);
    mean_pose = walk.frames[2].rotations;
  }
  // Tight tolerances, a weak rest prior toward the mean pose, and the hidden-joint and twist
  // priors' weights.
  MarkerSolveOptions Options(SolverKind solver, double hidden_weight, double twist_weight) const {
    MarkerSolveOptions options;
    options.solver = solver;
    options.ceres = DefaultFrameCeresOptions();
    options.dls.function_tolerance = options.ceres.function_tolerance = 1e-12;
    options.rest_rotation_weight = 0.05;
    options.hidden_rotation_weight = hidden_weight;
    options.twist_rotation_weight = twist_weight;
    options.rest_rotations = mean_pose;
    return options;
  }
};

TEST_P(MarkerFrameSolverTest, RecoversNoiseFreePosesFrameByFrame) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::mt19937 rng(1);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion truth = MakeDemoWalk(skeleton, 40, 30.0);
  MarkerSolveOptions options;
  options.solver = GetParam();
  options.ceres = DefaultFrameCeresOptions();
  MarkerFrameSolver solver(skeleton, markers, options);
  Pose pose = RestPose(skeleton);
  pose.translations[0] = truth.frames[0].translations[0] + Eigen::Vector3d(5, -3, 2);
  FkData solved(skeleton), expected(skeleton);
  for (int f = 0; f < truth.num_frames(); ++f) {
    FrameSolveReport report;
    const Status status = solver.Solve(Observe(skeleton, markers, truth.frames[f]), &pose, &report);
    ASSERT_TRUE(status.ok()) << status.message();
    ForwardKinematics(skeleton, pose, &solved);
    ForwardKinematics(skeleton, truth.frames[f], &expected);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      // Noise-free data: the solve converges to round-off (cm units).
      EXPECT_LT((solved.world_positions[j] - expected.world_positions[j]).norm(), 1e-5) << f << " " << j;
      EXPECT_LT(AngularDistance(solved.world_rotations[j], expected.world_rotations[j]), 1e-6) << f << " " << j;
    }
    EXPECT_LT(report.rms_marker_error, 1e-6) << report.brief;
  }
}

TEST_P(MarkerFrameSolverTest, MissingMarkersAreSkipped) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::mt19937 rng(2);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion truth = MakeDemoWalk(skeleton, 3, 30.0);
  MarkerSolveOptions options;
  options.solver = GetParam();
  options.ceres = DefaultFrameCeresOptions();
  MarkerFrameSolver solver(skeleton, markers, options);
  Pose pose = truth.frames[0];
  std::vector<Eigen::Vector3d> observed = Observe(skeleton, markers, truth.frames[2]);
  observed[0] = Eigen::Vector3d::Constant(std::nan(""));  // One root marker missing.
  observed[markers.FindMarker("LeftHand_1")] = Eigen::Vector3d::Constant(std::nan(""));
  FrameSolveReport report;
  ASSERT_TRUE(solver.Solve(observed, &pose, &report).ok());
  EXPECT_EQ(report.markers_used, markers.num_markers() - 2);
  EXPECT_LT(report.rms_marker_error, 1e-6);
}

// A joint whose markers are all missing is free: without the rest prior it keeps its warm
// start, with it (the only term on that joint) it goes to the prior's reference (zero
// rotations, or the given rest_rotations: a subject's mean pose); the observed markers are
// still fitted exactly (the prior costs nothing where they decide).
TEST_P(MarkerFrameSolverTest, RestPriorDecidesOnlyUnconstrainedJoints) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::mt19937 rng(5);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion truth = MakeDemoWalk(skeleton, 3, 30.0);
  const int hand = skeleton.FindJoint("LeftHand");
  ASSERT_GE(hand, 0);
  std::vector<Eigen::Vector3d> observed = Observe(skeleton, markers, truth.frames[2]);
  int hidden = 0;
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      if (a.joint != hand) continue;
      observed[m] = Eigen::Vector3d::Constant(std::nan(""));
      ++hidden;
    }
  }
  ASSERT_GT(hidden, 0);
  const Eigen::Quaterniond start(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  // A reference pose away from zero rotations: the observed pose (as a subject's mean pose
  // is near its poses), the hidden hand 2.5 rad from zero.
  QuaternionVector mean_pose = truth.frames[2].rotations;
  mean_pose[hand] = Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Eigen::Vector3d(-2, 1, 0.5).normalized()));
  for (bool given : {false, true}) {
    for (double rest_weight : {0.0, 0.05}) {
      MarkerSolveOptions options;
      options.solver = GetParam();
      options.ceres = DefaultFrameCeresOptions();
      options.rest_rotation_weight = rest_weight;
      if (given) options.rest_rotations = mean_pose;
      MarkerFrameSolver solver(skeleton, markers, options);
      Pose pose = truth.frames[0];
      pose.rotations[hand] = start;
      FrameSolveReport report;
      ASSERT_TRUE(solver.Solve(observed, &pose, &report).ok()) << report.brief;
      // The rest prior moves the other joints only as far as it trades marker error: under a
      // micron here (cm units; noise-free data, every other joint held by three markers).
      EXPECT_LT(report.rms_marker_error, 1e-4) << rest_weight << " " << report.brief;
      const Eigen::Quaterniond reference = given ? mean_pose[hand] : Eigen::Quaterniond::Identity();
      if (rest_weight == 0.0) {
        EXPECT_LT(AngularDistance(pose.rotations[hand], start), 1e-8);
      } else {
        // The solvers' tolerances, in radians.
        EXPECT_LT(AngularDistance(pose.rotations[hand], reference), 1e-4) << given << " " << report.brief;
      }
    }
  }
  // A reference of another size than the skeleton is an error, not a silent identity.
  MarkerSolveOptions options;
  options.solver = GetParam();
  options.ceres = DefaultFrameCeresOptions();
  options.rest_rotation_weight = 0.05;
  options.rest_rotations.assign(skeleton.num_joints() - 1, Eigen::Quaterniond::Identity());
  MarkerFrameSolver solver(skeleton, markers, options);
  Pose pose = truth.frames[0];
  FrameSolveReport report;
  const Status status = solver.Solve(observed, &pose, &report);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("rest pose"), std::string::npos) << status.message();
}

// A hidden joint -- its own markers all missing, the bones below it observed (a clavicle
// without its shoulder marker, hinged on by the arm) -- is held toward the reference by
// hidden_rotation_weight, not placed by the arm alone: here the arm's markers say the
// shoulder is 0.3 rad from the subject's mean pose, and the weak rest prior follows them,
// the hidden-joint prior keeps it nearer the mean. While one of its own markers is observed
// the joint solves exactly as without it (the same solver, frame after frame).
TEST_P(MarkerFrameSolverTest, HiddenJointIsHeldAtTheReference) {
  const ShoulderFixture arm;
  ASSERT_GE(arm.shoulder, 0);
  Pose truth = arm.walk.frames[2];
  truth.rotations[arm.shoulder] = arm.mean_pose[arm.shoulder] * Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  const std::vector<Eigen::Vector3d> all = Observe(arm.skeleton, arm.markers, truth);
  std::vector<Eigen::Vector3d> hidden = all;
  for (int m = 0; m < arm.markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : arm.markers.marker(m).attachments) {
      if (a.joint == arm.shoulder) hidden[m] = Eigen::Vector3d::Constant(std::nan(""));
    }
  }
  auto options_with = [&](double hidden_weight) { return arm.Options(GetParam(), hidden_weight, 0.0); };
  MarkerFrameSolver weak(arm.skeleton, arm.markers, options_with(0.0));
  MarkerFrameSolver held(arm.skeleton, arm.markers, options_with(20.0));
  Pose a = arm.walk.frames[2], b = arm.walk.frames[2];
  FrameSolveReport report;
  ASSERT_TRUE(weak.Solve(hidden, &a, &report).ok()) << report.brief;
  ASSERT_TRUE(held.Solve(hidden, &b, &report).ok()) << report.brief;
  EXPECT_EQ(report.held_joints, std::vector<int>{arm.shoulder});  // Reported as held.
  // The arm's nine markers place the shoulder: the weak prior lands near the truth.
  EXPECT_LT(AngularDistance(a.rotations[arm.shoulder], truth.rotations[arm.shoulder]), 0.01);
  EXPECT_GT(AngularDistance(a.rotations[arm.shoulder], arm.mean_pose[arm.shoulder]), 0.28);
  // Held: at least twice nearer the mean pose than the arm alone would put it.
  EXPECT_LT(AngularDistance(b.rotations[arm.shoulder], arm.mean_pose[arm.shoulder]), 0.15);
  // Own markers back: the same pose as without the hidden-joint prior.
  a = b = arm.walk.frames[2];
  ASSERT_TRUE(weak.Solve(all, &a, &report).ok()) << report.brief;
  ASSERT_TRUE(held.Solve(all, &b, &report).ok()) << report.brief;
  EXPECT_TRUE(report.held_joints.empty());
  for (int j = 0; j < arm.skeleton.num_joints(); ++j) {
    EXPECT_LT(AngularDistance(a.rotations[j], b.rotations[j]), 1e-12) << j;
  }
  EXPECT_LT(AngularDistance(b.rotations[arm.shoulder], truth.rotations[arm.shoulder]), 0.01);
  // Without a given reference the hidden-joint prior is off (zero rotations are no mean pose).
  MarkerSolveOptions no_reference = options_with(20.0);
  no_reference.rest_rotations.clear();
  MarkerFrameSolver unreferenced(arm.skeleton, arm.markers, no_reference);
  MarkerSolveOptions plain = options_with(0.0);
  plain.rest_rotations.clear();
  MarkerFrameSolver reference_free(arm.skeleton, arm.markers, plain);
  a = b = arm.walk.frames[2];
  ASSERT_TRUE(reference_free.Solve(hidden, &a, &report).ok()) << report.brief;
  ASSERT_TRUE(unreferenced.Solve(hidden, &b, &report).ok()) << report.brief;
  EXPECT_LT(AngularDistance(a.rotations[arm.shoulder], b.rotations[arm.shoulder]), 1e-12);
}

// A joint that keeps one of its own markers (the others missing) is held with
// twist_rotation_weight about the line to that marker only, where the markers below observe that
// twist by less than kTwistObservedFraction of the weight: the arm's markers turn the shoulder 0.3 rad about that
// line away from the mean pose and the weak rest prior follows them, the twist prior keeps it
// nearer the mean; a 0.3 rad turn about a normal direction (which the seen marker itself shows)
// is recovered as without the prior. A weight below the arm's observability holds nothing.
TEST_P(MarkerFrameSolverTest, OneSeenMarkerHoldsOnlyTheTwistAboutIt) {
  const ShoulderFixture arm;
  ASSERT_GE(arm.shoulder, 0);
  int kept = -1;
  std::vector<int> dropped;
  for (int m = 0; m < arm.markers.num_markers(); ++m) {
    for (const MarkerAttachment& a : arm.markers.marker(m).attachments) {
      if (a.joint != arm.shoulder) continue;
      if (kept < 0) {
        kept = m;
      } else {
        dropped.push_back(m);
      }
    }
  }
  ASSERT_GE(kept, 0);
  ASSERT_GE(dropped.size(), 1u);
  const Eigen::Vector3d u = arm.markers.marker(kept).attachments[0].offset.normalized();
  auto options_with = [&](double twist_weight) { return arm.Options(GetParam(), 20.0, twist_weight); };
  // The arm observes the twist (its ball joint off the line): held only by a weight well above
  // that (at the warm start, the markers below the shoulder all observed).
  const double observed = TwistObservability(arm.skeleton, arm.markers, arm.walk.frames[2], arm.shoulder, u);
  ASSERT_GT(observed, 1.0);
  MarkerFrameSolver weak(arm.skeleton, arm.markers, options_with(0.0));
  MarkerFrameSolver below(arm.skeleton, arm.markers, options_with(0.9 * observed / kTwistObservedFraction));
  MarkerFrameSolver held(arm.skeleton, arm.markers, options_with(2.0 * observed / kTwistObservedFraction));
  auto solve = [&](MarkerFrameSolver& solver, const Eigen::Vector3d& turn, FrameSolveReport* report) {
    Pose truth = arm.walk.frames[2];
    truth.rotations[arm.shoulder] = arm.mean_pose[arm.shoulder] * Eigen::Quaterniond(Eigen::AngleAxisd(0.3, turn));
    std::vector<Eigen::Vector3d> observed = Observe(arm.skeleton, arm.markers, truth);
    for (int m : dropped) observed[m] = Eigen::Vector3d::Constant(std::nan(""));
    Pose pose = arm.walk.frames[2];
    EXPECT_TRUE(solver.Solve(observed, &pose, report).ok()) << report->brief;
    return std::make_pair(pose.rotations[arm.shoulder], truth.rotations[arm.shoulder]);
  };
  FrameSolveReport report;
  const auto [free_twist, truth_twist] = solve(weak, u, &report);
  EXPECT_TRUE(report.twist_held_joints.empty());
  solve(below, u, &report);
  EXPECT_TRUE(report.twist_held_joints.empty());
  const auto [held_twist, unused] = solve(held, u, &report);
  EXPECT_EQ(report.twist_held_joints, std::vector<int>{arm.shoulder});
  EXPECT_TRUE(report.held_joints.empty());
  // The arm places the twist: the weak prior lands near the truth, 0.3 rad from the mean.
  EXPECT_LT(AngularDistance(free_twist, truth_twist), 0.01);
  EXPECT_GT(AngularDistance(free_twist, arm.mean_pose[arm.shoulder]), 0.28);
  // Held about u: at least twice nearer the mean pose.
  EXPECT_LT(AngularDistance(held_twist, arm.mean_pose[arm.shoulder]), 0.15);
  // A turn about a direction normal to u moves the seen marker: recovered with the prior on.
  const auto [held_swing, truth_swing] = solve(held, u.unitOrthogonal(), &report);
  EXPECT_LT(AngularDistance(held_swing, truth_swing), 0.01);
  // Over a sequence, the frames each joint was held so are counted (the reports' figure).
  std::vector<std::vector<Eigen::Vector3d>> frames;
  for (const Pose& pose : arm.walk.frames) {
    frames.push_back(Observe(arm.skeleton, arm.markers, pose));
    for (int m : dropped) frames.back()[m] = Eigen::Vector3d::Constant(std::nan(""));
  }
  Motion motion;
  SequenceSolveReport sequence;
  ASSERT_TRUE(SolveSequence(arm.skeleton, arm.markers, frames, options_with(2.0 * observed / kTwistObservedFraction),
                            arm.walk.frames[0], &motion, &sequence).ok());
  ASSERT_EQ(sequence.twist_held_frames.size(), static_cast<size_t>(arm.skeleton.num_joints()));
  for (int j = 0; j < arm.skeleton.num_joints(); ++j) {
    EXPECT_EQ(sequence.twist_held_frames[j], j == arm.shoulder ? 3 : 0) << arm.skeleton.name(j);
  }
}

// A marker set without the left arm's markers (a sparse protocol's unobserved arm): no
// marker moves the arm, so a sequence solve starts it, and keeps it, at the rest prior's
// reference (the subject's mean pose) when one is given, at the initial pose's otherwise.
// (Started at zero rotations, it stayed there: a T-pose arm for an ASF subject.)
TEST_P(MarkerFrameSolverTest, AJointNoMarkerMovesStartsAndStaysAtTheReference) {
  const ShoulderFixture arm;
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < arm.markers.num_markers(); ++m) {
    const int j = arm.markers.marker(m).attachments[0].joint;
    if (j < arm.shoulder || j >= arm.skeleton.subtree_end(arm.shoulder)) specs.push_back(arm.markers.marker(m));
  }
  MarkerSet armless;
  ASSERT_TRUE(MarkerSet::Create(arm.skeleton, specs, &armless).ok());
  std::vector<std::vector<Eigen::Vector3d>> frames;
  for (const Pose& pose : arm.walk.frames) frames.push_back(Observe(arm.skeleton, armless, pose));
  // The mean pose's arm 2 rad away from zero rotations, so starting at zero cannot pass.
  QuaternionVector mean_pose = arm.mean_pose;
  for (int j = arm.shoulder; j < arm.skeleton.subtree_end(arm.shoulder); ++j) {
    mean_pose[j] = Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -1, 2).normalized()));
  }
  for (const bool given : {true, false}) {
    MarkerSolveOptions options = arm.Options(GetParam(), 0.0, 0.0);
    options.rest_rotations = given ? mean_pose : QuaternionVector();
    Motion motion;
    SequenceSolveReport sequence;
    ASSERT_TRUE(SolveSequence(arm.skeleton, armless, frames, options, RestPose(arm.skeleton), &motion, &sequence).ok());
    for (const Pose& pose : motion.frames) {
      for (int j = arm.shoulder; j < arm.skeleton.subtree_end(arm.shoulder); ++j) {
        const Eigen::Quaterniond expected = given ? mean_pose[j] : Eigen::Quaterniond::Identity();
        EXPECT_LT(AngularDistance(pose.rotations[j], expected), 1e-6) << given << " " << arm.skeleton.name(j);
      }
    }
    // The observed joints are solved as before: noise-free markers fitted to round-off.
    EXPECT_LT(sequence.rms_marker_error, 1e-4) << given;
  }
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, MarkerFrameSolverTest,
                         ::testing::Values(SolverKind::kCeres, SolverKind::kDls, SolverKind::kDlsGeneric),
                         [](const auto& info) { return std::string(SolverKindName(info.param)); });

// The demo skeleton with ASF-like dofs: hinges (one axis), two-axis joints, a joint
// without dofs, and free ones.
Skeleton DemoSkeletonWithDofs() {
  const Skeleton demo = MakeDemoSkeleton();
  std::vector<JointSpec> joints;
  for (int j = 0; j < demo.num_joints(); ++j) {
    joints.push_back(demo.joint(j));
    const std::string& name = joints.back().name;
    if (name == "LeftLeg" || name == "RightLeg" || name == "LeftForeArm") joints.back().rotation_axes = std::vector<int>{0};
    if (name == "LeftFoot" || name == "RightForeArm") joints.back().rotation_axes = std::vector<int>{0, 2};
    if (name == "Neck") joints.back().rotation_axes = std::vector<int>{};
  }
  Skeleton skeleton;
  EXPECT_TRUE(Skeleton::Create(joints, demo.end_sites(), demo.unit(), &skeleton).ok());
  return skeleton;
}

// The lean kernel and the generic DLS solver run the same iterations (shared loop, same
// stopping rules) on the same residuals: same iteration counts, costs and poses to
// round-off, frame by frame, with priors (previous frame and rest), limits, a robust loss and missing markers.
TEST(MarkerFrameSolver, LeanAndGenericDlsTakeTheSameSteps) {
  for (bool dofs : {false, true}) {
    SCOPED_TRACE(dofs ? "ASF-like dofs" : "free joints");
    const Skeleton skeleton = dofs ? DemoSkeletonWithDofs() : MakeDemoSkeleton();
    std::mt19937 rng(4);
    const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
    const Motion truth = MakeDemoWalk(MakeDemoSkeleton(), 12, 30.0);
    std::normal_distribution<double> noise(0.0, 0.3);
    for (const char* loss : {"none", "cauchy"}) {
      MarkerSolveOptions options;
      options.dls.function_tolerance = 1e-6;
      options.prior_rotation_weight = 2.0;
      options.prior_translation_weight = 0.1;
      options.rest_rotation_weight = 0.2;
      for (int j = 0; j < skeleton.num_joints(); ++j) {  // A reference other than zero rotations.
        options.rest_rotations.push_back(ExpMap(Eigen::Vector3d(0.1 * j, -0.05, 0.2)));
      }
      options.loss = loss;
      options.loss_scale = 1.0;
      options.solver = SolverKind::kDls;
      MarkerFrameSolver lean(skeleton, markers, options);
      options.solver = SolverKind::kDlsGeneric;
      MarkerFrameSolver generic(skeleton, markers, options);
      Pose a = RestPose(skeleton), b = RestPose(skeleton);
      a.translations[0] = b.translations[0] = truth.frames[0].translations[0];
      for (int f = 0; f < truth.num_frames(); ++f) {
        std::vector<Eigen::Vector3d> observed = Observe(skeleton, markers, truth.frames[f]);
        for (auto& x : observed) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        if (f % 3 == 1) observed[f % markers.num_markers()] = Eigen::Vector3d::Constant(std::nan(""));
        FrameSolveReport ra, rb;
        ASSERT_TRUE(lean.Solve(observed, &a, &ra).ok()) << ra.brief;
        ASSERT_TRUE(generic.Solve(observed, &b, &rb).ok()) << rb.brief;
        EXPECT_EQ(ra.iterations, rb.iterations) << f << "\n" << ra.brief << "\n" << rb.brief;
        // The same linear algebra in another order: round-off, amplified by a few steps.
        EXPECT_NEAR(ra.final_cost, rb.final_cost, 1e-9 * (1.0 + rb.final_cost)) << f << " " << loss;
        EXPECT_LT((a.translations[0] - b.translations[0]).norm(), 1e-7) << f;
        for (int j = 0; j < skeleton.num_joints(); ++j) {
          EXPECT_LT(AngularDistance(a.rotations[j], b.rotations[j]), 1e-8) << f << " joint " << j;
        }
      }
    }
  }
}

TEST(MarkerFrameSolver, SolversAgreeOnFinalCostWithNoise) {
  const Skeleton skeleton = MakeDemoSkeleton();
  std::mt19937 rng(3);
  const MarkerSet markers = MakeSyntheticMarkerSet(skeleton, 3, rng());
  const Motion truth = MakeDemoWalk(skeleton, 10, 30.0);
  std::normal_distribution<double> noise(0.0, 0.3);  // 3 mm
  MarkerSolveOptions ceres_options, dls_options;
  ceres_options.ceres = DefaultFrameCeresOptions();
  dls_options.solver = SolverKind::kDls;
  MarkerFrameSolver ceres_solver(skeleton, markers, ceres_options), dls_solver(skeleton, markers, dls_options);
  Pose ceres_pose = truth.frames[0], dls_pose = truth.frames[0];
  for (int f = 0; f < truth.num_frames(); ++f) {
    std::vector<Eigen::Vector3d> observed = Observe(skeleton, markers, truth.frames[f]);
    for (auto& x : observed) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    FrameSolveReport a, b;
    ASSERT_TRUE(ceres_solver.Solve(observed, &ceres_pose, &a).ok());
    ASSERT_TRUE(dls_solver.Solve(observed, &dls_pose, &b).ok());
    // Issue 3: at convergence the two agree on the final cost within 1 %.
    EXPECT_NEAR(a.final_cost, b.final_cost, 0.01 * a.final_cost) << a.brief << "\n" << b.brief;
  }
}

}  // namespace
}  // namespace mocapsolve
