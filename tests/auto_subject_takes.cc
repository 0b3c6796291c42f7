#include "tests/auto_subject_takes.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "pipeline/shipped_templates.h"

namespace mocapsolve::testing {

namespace {

// The walk of TemplateWalkTake; from frame `bend_from` on (when >= 0) the right elbow bends
// and straightens again (70 degrees at most) where it held the mean pose before, and the
// right wrist holds it throughout.
MarkerTrajectories WalkTake(int frames, bool renamed, int bend_from) {
  Subject templ;
  EXPECT_TRUE(DefaultTemplateSubject(&templ).ok());
  const Skeleton& skeleton = templ.skeleton;
  const MarkerSet& markers = templ.markers;
  std::vector<std::string> labels;
  std::vector<int> order(markers.num_markers());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  for (int m = 0; m < markers.num_markers(); ++m) {
    labels.push_back(renamed ? "M" + std::to_string(order[m]) : markers.label(m));
  }
  if (bend_from >= 0) labels.push_back(renamed ? "M" + std::to_string(markers.num_markers()) : "ROLC");
  MarkerTrajectories take(labels, frames);
  take.frame_rate = 60.0;
  take.unit = Millimetres();
  const double mm = skeleton.unit().metres_per_unit * 1000.0;
  const int elbow = skeleton.FindJoint("rradius"), wrist = skeleton.FindJoint("rwrist");
  const int shoulder = skeleton.FindJoint("rhumerus");
  EXPECT_TRUE(bend_from < 0 || (elbow >= 0 && wrist >= 0 && shoulder >= 0));
  FkData fk(skeleton);
  // ROLC: a marker on the forearm just behind the elbow (an olecranon), in the mean pose 35
  // mm up the upper arm from the elbow and 15 mm off its axis: nearer the upper arm's bone
  // than the forearm's, so only frames that bend the elbow tell which it rides on.
  Eigen::Vector3d olecranon = Eigen::Vector3d::Zero();  // In rradius' frame.
  if (bend_from >= 0) {
    Pose mean = RestPose(skeleton);
    for (int j = 1; j < skeleton.num_joints(); ++j) mean.rotations[j] = templ.mean_pose[j];
    ForwardKinematics(skeleton, mean, &fk);
    const Eigen::Vector3d at = fk.world_positions[elbow];
    const Eigen::Vector3d up = (fk.world_positions[shoulder] - at).normalized();
    const Eigen::Vector3d off = up.cross(fk.world_positions[wrist] - at).normalized();
    olecranon = fk.world_rotations[elbow].inverse() * ((35.0 * up + 15.0 * off) / mm);
  }
  for (int f = 0; f < frames; ++f) {
    const double phase = 2.0 * M_PI * (f / take.frame_rate) / 1.1;  // A 1.1 s stride.
    Pose pose = RestPose(skeleton);
    pose.translations[0] = Eigen::Vector3d(0.0, 0.3 * std::cos(2.0 * phase), 1000.0 * f / take.frame_rate / mm);
    pose.rotations[0] = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * std::sin(phase), Eigen::Vector3d::UnitY()));
    for (int j = 1; j < skeleton.num_joints(); ++j) {
      if (skeleton.num_rotation_dofs(j) == 0) continue;
      // About the joint's last dof axis, so the pose stays within its dofs (mean * R_last).
      const double degrees = skeleton.num_rotation_dofs(j) == 3 && j >= 11 && j <= 16 ? 5.0 : 18.0;
      double angle = degrees * M_PI / 180.0 * std::sin(phase + 0.9 * j);
      if (bend_from >= 0 && (j == elbow || j == wrist)) {
        const double t = f < bend_from || j == wrist ? 0.0 : (f - bend_from) / std::max(1.0, frames - 1.0 - bend_from);
        angle = 70.0 * M_PI / 180.0 * std::sin(M_PI * t);
      }
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(skeleton.rotation_axes(j).back());
      pose.rotations[j] = templ.mean_pose[j] * Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis));
    }
    ForwardKinematics(skeleton, pose, &fk);
    for (int m = 0; m < markers.num_markers(); ++m) {
      const Eigen::Vector3d x = markers.Position(m, fk) * mm;
      take.SetSample(f, m, Eigen::Vector3d(x.x(), -x.z(), x.y()));
    }
    if (bend_from >= 0) {
      const Eigen::Vector3d x = (fk.world_positions[elbow] + fk.world_rotations[elbow] * olecranon) * mm;
      take.SetSample(f, markers.num_markers(), Eigen::Vector3d(x.x(), -x.z(), x.y()));
    }
  }
  return take;
}

}  // namespace

MarkerTrajectories TemplateWalkTake(int frames, bool renamed) { return WalkTake(frames, renamed, -1); }

MarkerTrajectories TemplateWalkTakeBendingLate(int frames, int bend_from, bool renamed) {
  return WalkTake(frames, renamed, bend_from);
}

MarkerTrajectories KeepTakeMarkers(const MarkerTrajectories& take, const std::vector<std::string>& labels,
                                   const std::vector<std::string>& renamed) {
  MarkerTrajectories kept(renamed.empty() ? labels : renamed, take.num_frames());
  kept.frame_rate = take.frame_rate;
  kept.unit = take.unit;
  for (size_t k = 0; k < labels.size(); ++k) {
    const int m = take.FindMarker(labels[k]);
    EXPECT_GE(m, 0) << labels[k];
    for (int f = 0; m >= 0 && f < take.num_frames(); ++f) {
      if (take.valid(f, m)) kept.SetSample(f, static_cast<int>(k), take.position(f, m));
    }
  }
  return kept;
}

MarkerTrajectories RandomPointsTake(int frames, int points) {
  std::vector<std::string> labels;
  for (int m = 0; m < points; ++m) labels.push_back("P" + std::to_string(m));
  MarkerTrajectories take(labels, frames);
  take.frame_rate = 60.0;
  take.unit = Millimetres();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> box(0.0, 2000.0), step(-30.0, 30.0);
  std::vector<Eigen::Vector3d> at(points);
  for (Eigen::Vector3d& x : at) x = Eigen::Vector3d(box(rng), box(rng), box(rng));
  for (int f = 0; f < frames; ++f) {
    for (int m = 0; m < points; ++m) {
      at[m] += Eigen::Vector3d(step(rng), step(rng), step(rng));
      take.SetSample(f, m, at[m]);
    }
  }
  return take;
}

}  // namespace mocapsolve::testing
