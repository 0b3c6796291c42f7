// CompactMotion: a Motion stored in a quarter of the memory, for the long-lived copies of
// a long take (the solve kept for writing, a character's retargeted take, the reference
// solves inside repair), expanded frame by frame where it is read.
//
// Per frame: each joint's rotation as a float quaternion (4 x 4 B) and the translations
// that vary over the take as float (3 x 4 B each: the root's, usually alone); a joint
// whose translation is the same in every frame keeps it once, in double, exactly. The
// CMU subject's 31 joints: 31 x 16 + 12 = 508 B per frame instead of 31 x (24 + 32) B in
// two heap blocks (~1.8 KB); Xbot's 65: 1,052 B instead of ~3.7 KB.
//
// Accuracy: a float has a 24-bit mantissa, so a stored value is within 2^-24 (6e-8) of
// the double relative to its magnitude: a root position 10 m from the origin is within
// 0.6 um; a rotation is expanded as the float quaternion renormalized in double, within
// ~1e-7 rad of the original, which moves a point 2 m from its joint by < 0.3 um. Both are
// far inside the 0.01 mm to which the pipeline's outputs are compared.
#ifndef MOCAPSOLVE_KINEMATICS_COMPACT_MOTION_H_
#define MOCAPSOLVE_KINEMATICS_COMPACT_MOTION_H_

#include <cstddef>
#include <vector>

#include "kinematics/motion.h"

namespace mocapsolve {

class CompactMotion {
 public:
  CompactMotion() = default;
  // Every frame of `motion` (all of one joint count), which may be freed afterwards.
  explicit CompactMotion(const Motion& motion);

  double frame_rate() const { return frame_rate_; }
  int num_frames() const { return num_frames_; }
  int num_joints() const { return num_joints_; }
  bool empty() const { return num_frames_ == 0; }

  // Frame f expanded into *pose (its vectors resized once, then reused).
  void Frame(int f, Pose* pose) const;
  Pose Frame(int f) const;
  // One joint of frame f.
  Eigen::Quaterniond Rotation(int f, int joint) const;
  Eigen::Vector3d Translation(int f, int joint) const;
  // Frames [first, first + count) of `motion` appended (a take assembled window by
  // window, pipeline/take_windows.h); the first append sets the frame rate and joint count.
  // A joint whose translation was fixed and moves in the new frames gets a column (the
  // frames before keep their fixed value), so the result is as if built whole.
  void Append(const Motion& motion, int first, int count);
  // Room for `frames` frames in all, so that appends do not grow the arrays by doubling.
  void Reserve(int frames);
  // Every frame expanded.
  Motion ToMotion() const;
  // Heap bytes held (for the figures in BENCHMARKS.md and tests).
  size_t bytes() const;

 private:
  int num_moving() const;
  double frame_rate_ = 0.0;
  int num_frames_ = 0, num_joints_ = 0;
  int reserved_frames_ = 0;  // Reserve's, for the arrays made at the first append.
  // Per joint: -1 when its translation is fixed (fixed_translations_[j]), else its column
  // in the per-frame float translations.
  std::vector<int> moving_column_;
  Vector3dVector fixed_translations_;
  std::vector<float> rotations_;     // [frame][joint] x (w, x, y, z).
  std::vector<float> translations_;  // [frame][moving joint] x (x, y, z).
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_COMPACT_MOTION_H_
