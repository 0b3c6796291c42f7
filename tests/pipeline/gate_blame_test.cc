// The quality gate's blame: the marker whose samples disagree with the solved motion is
// named first with its share and worst frames, and the advice tells how to read it as
// missing; error spread over every marker reads as a subject that does not fit.
#include "pipeline/gate_blame.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "kinematics/demo_character.h"
#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/marker_solve/synthetic_marker_set.h"

namespace mocapsolve {
namespace {

struct Take {
  Skeleton skeleton;
  MarkerSet markers;
  Motion motion;
  std::vector<std::vector<Eigen::Vector3d>> observed;  // The model's positions on `motion`.
};

Take MovingTake(int frames) {
  Take take;
  take.skeleton = MakeDemoSkeleton();
  take.markers = MakeSyntheticMarkerSet(take.skeleton, 2, 7);
  take.motion.frame_rate = 60.0;
  FkData fk(take.skeleton);
  for (int f = 0; f < frames; ++f) {
    Pose pose = RestPose(take.skeleton);
    for (int j = 0; j < take.skeleton.num_joints(); ++j) {
      pose.rotations[j] = ExpMap(Eigen::Vector3d(0.3 * std::sin(0.05 * f + j), 0.2 * std::cos(0.03 * f), 0.1));
    }
    take.motion.frames.push_back(pose);
    ForwardKinematics(take.skeleton, pose, &fk);
    std::vector<Eigen::Vector3d> row;
    for (int m = 0; m < take.markers.num_markers(); ++m) row.push_back(take.markers.Position(m, fk));
    take.observed.push_back(row);
  }
  return take;
}

TEST(GateBlame, AMarkerThatCameOffIsNamedWithItsFrames) {
  Take take = MovingTake(300);
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.002);  // 2 mm at mm = 1000 per unit (metres).
  for (auto& row : take.observed) {
    for (Eigen::Vector3d& x : row) x += Eigen::Vector3d(noise(random), noise(random), noise(random));
  }
  const int off = 5;
  for (int f = 200; f < 260; ++f) take.observed[f][off] += Eigen::Vector3d(0.3, 0.0, 0.0);  // 30 cm, one second.
  take.observed[10][off] = Eigen::Vector3d::Constant(std::nan(""));                         // A gap: not counted.
  const std::vector<MarkerBlame> blame = BlameMarkers(take.skeleton, take.markers, take.observed, take.motion, 1000.0);
  ASSERT_EQ(blame.size(), static_cast<size_t>(take.markers.num_markers()));
  EXPECT_EQ(blame[0].label, take.markers.label(off));
  EXPECT_GT(blame[0].share, 0.95);
  EXPECT_NEAR(blame[0].rms_mm, 300.0 * std::sqrt(60.0 / 299.0), 5.0);
  EXPECT_EQ(blame[0].worst_first, 200);
  EXPECT_EQ(blame[0].worst_last, 259);
  for (size_t k = 1; k < blame.size(); ++k) EXPECT_LT(blame[k].rms_mm, 5.0);
  const std::string advice = GateAdvice(blame, "take.c3d");
  EXPECT_NE(advice.find("--ignore_markers=" + take.markers.label(off) + " "), std::string::npos) << advice;
  EXPECT_NE(advice.find("worst frames 200-259"), std::string::npos) << advice;
  EXPECT_NE(advice.find("--markers=take.c3d"), std::string::npos) << advice;
  // A subject fitted on this take (--subject=auto): the markers, not another fit.
  const std::string fitted = GateAdvice(blame, "take.c3d", true);
  EXPECT_NE(fitted.find("--ignore_markers=" + take.markers.label(off) + " "), std::string::npos) << fitted;
  EXPECT_EQ(fitted.find("fit_skeleton"), std::string::npos) << fitted;
}

TEST(GateBlame, ErrorOnEveryMarkerIsASubjectThatDoesNotFit) {
  Take take = MovingTake(120);
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0.0, 0.02);
  for (auto& row : take.observed) {
    for (Eigen::Vector3d& x : row) x += Eigen::Vector3d(noise(random), noise(random), noise(random));
  }
  const std::vector<MarkerBlame> blame = BlameMarkers(take.skeleton, take.markers, take.observed, take.motion, 1000.0);
  double total = 0.0;
  for (const MarkerBlame& b : blame) total += b.share;
  EXPECT_NEAR(total, 1.0, 1e-9);
  const std::string advice = GateAdvice(blame, "take.c3d");
  EXPECT_NE(advice.find("spread over the markers"), std::string::npos) << advice;
  EXPECT_EQ(advice.find("--ignore_markers"), std::string::npos) << advice;
  const std::string fitted = GateAdvice(blame, "take.c3d", true);
  EXPECT_NE(fitted.find("--fit_max_frames=0"), std::string::npos) << fitted;
  EXPECT_EQ(fitted.find("fit_skeleton"), std::string::npos) << fitted;
}

}  // namespace
}  // namespace mocapsolve
