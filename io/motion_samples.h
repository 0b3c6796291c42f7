// A clip's joint samples read one (frame, joint) at a time, from a Motion or from a
// CompactMotion (kinematics/compact_motion.h), so that a writer templated on the two
// (io/gltf_writer.cc, io/fbx_writer.cc) writes a long take without expanding it whole
// (a Motion holds ~3.6 KB per frame of a 65-joint character; a CompactMotion ~1 KB).
//   rotation(f, j), translation(f, j): joint j's local rotation and translation in frame f.
//   Validate(skeleton): what the readers accept of the clip (io/input_limits.h and
//   ValidateMotion), the error naming the frame and joint; the caller prefixes the file.
#ifndef MOCAPSOLVE_IO_MOTION_SAMPLES_H_
#define MOCAPSOLVE_IO_MOTION_SAMPLES_H_

#include <Eigen/Geometry>

#include "kinematics/compact_motion.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

class MotionSamples {
 public:
  explicit MotionSamples(const Motion& motion) : motion_(motion) {}
  double frame_rate() const { return motion_.frame_rate; }
  int num_frames() const { return motion_.num_frames(); }
  const Eigen::Quaterniond& rotation(int f, int j) const { return motion_.frames[f].rotations[j]; }
  const Eigen::Vector3d& translation(int f, int j) const { return motion_.frames[f].translations[j]; }
  Status Validate(const Skeleton& skeleton) const;

 private:
  const Motion& motion_;
};

class CompactSamples {
 public:
  explicit CompactSamples(const CompactMotion& motion) : motion_(motion) {}
  double frame_rate() const { return motion_.frame_rate(); }
  int num_frames() const { return motion_.num_frames(); }
  Eigen::Quaterniond rotation(int f, int j) const { return motion_.Rotation(f, j); }
  Eigen::Vector3d translation(int f, int j) const { return motion_.Translation(f, j); }
  // The checks of MotionSamples, frame by frame.
  Status Validate(const Skeleton& skeleton) const;

 private:
  const CompactMotion& motion_;
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MOTION_SAMPLES_H_
