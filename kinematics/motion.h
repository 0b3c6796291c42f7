// Pose and Motion: the animated state of a Skeleton.
//
// Pose: per joint j, the local translation t_j (file units; equal to the skeleton's rest
// offset for joints whose translation is not animated; the root's is its position in
// the world) and the local rotation R_j (unit quaternion, applied after the rest
// rotation, see skeleton.h). A Motion is a frame rate and a sequence of poses.
#ifndef MOCAPSOLVE_KINEMATICS_MOTION_H_
#define MOCAPSOLVE_KINEMATICS_MOTION_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/StdVector>

#include "kinematics/skeleton.h"

namespace mocapsolve {

using QuaternionVector = std::vector<Eigen::Quaterniond>;
using Vector3dVector = std::vector<Eigen::Vector3d>;

struct Pose {
  Vector3dVector translations;  // #J local translations.
  QuaternionVector rotations;   // #J local rotations.
};

// Rest offsets as translations, identity rotations.
Pose RestPose(const Skeleton& skeleton);

struct Motion {
  double frame_rate = 0.0;  // Frames per second.
  std::vector<Pose> frames;

  int num_frames() const { return static_cast<int>(frames.size()); }
  double duration_seconds() const {
    return frame_rate > 0.0 && !frames.empty() ? (num_frames() - 1) / frame_rate : 0.0;
  }
};

// Makes every joint's rotation series sign-continuous over time (q and -q are the same
// rotation; a continuous series can be differenced and interpolated).
void MakeSignContinuous(Motion* motion);

// Checks sizes against the skeleton and that every value is finite and every rotation
// a unit quaternion (to 1e-6); the message names the first bad frame and joint.
Status ValidateMotion(const Skeleton& skeleton, const Motion& motion);
// The same for one pose; the message starts with `where` ("frame 3", "pose").
Status ValidatePose(const Skeleton& skeleton, const Pose& pose, const std::string& where);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_MOTION_H_
