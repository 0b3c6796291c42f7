#include "signal/bad_interval_detection.h"

#include <string>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"

namespace mocapsolve {

namespace {

const Pose& PoseOf(const Motion& motion, int f, Pose*) { return motion.frames[f]; }
const Pose& PoseOf(const CompactMotion& motion, int f, Pose* scratch) {
  motion.Frame(f, scratch);
  return *scratch;
}

template <class Naive>
Status DetectBad(const Skeleton& skeleton, const Naive& naive, const Motion& reference,
                 const BadJointThresholds& thresholds, std::vector<std::vector<char>>* bad_joints) {
  if (naive.num_frames() != reference.num_frames()) {
    return Status::Error("DetectBad: naive solve has " + std::to_string(naive.num_frames()) +
                         " frames, reference " + std::to_string(reference.num_frames()));
  }
  const int nj = skeleton.num_joints();
  bad_joints->assign(naive.num_frames(), std::vector<char>(nj, 0));
  FkData a(skeleton), b(skeleton);
  Pose scratch;
  for (int f = 0; f < naive.num_frames(); ++f) {
    ForwardKinematics(skeleton, PoseOf(naive, f, &scratch), &a);
    ForwardKinematics(skeleton, reference.frames[f], &b);
    for (int j = 0; j < nj; ++j) {
      const bool far = (a.world_positions[j] - b.world_positions[j]).norm() > thresholds.position;
      const bool turned = AngularDistance(a.world_rotations[j], b.world_rotations[j]) > thresholds.rotation_rad;
      (*bad_joints)[f][j] = far || turned;
    }
  }
  return Status::Ok();
}

}  // namespace

Status DetectBadJoints(const Skeleton& skeleton, const Motion& naive, const Motion& reference,
                       const BadJointThresholds& thresholds, std::vector<std::vector<char>>* bad_joints) {
  return DetectBad(skeleton, naive, reference, thresholds, bad_joints);
}

Status DetectBadJoints(const Skeleton& skeleton, const CompactMotion& naive, const Motion& reference,
                       const BadJointThresholds& thresholds, std::vector<std::vector<char>>* bad_joints) {
  return DetectBad(skeleton, naive, reference, thresholds, bad_joints);
}

std::vector<std::vector<char>> BadMarkerSamples(const MarkerSet& markers,
                                                const std::vector<std::vector<char>>& bad_joints) {
  std::vector<std::vector<char>> bad(bad_joints.size(), std::vector<char>(markers.num_markers(), 0));
  for (size_t f = 0; f < bad_joints.size(); ++f) {
    for (int m = 0; m < markers.num_markers(); ++m) {
      for (const MarkerAttachment& a : markers.marker(m).attachments) {
        if (a.weight > 0.0 && bad_joints[f][a.joint]) bad[f][m] = 1;
      }
    }
  }
  return bad;
}

}  // namespace mocapsolve
