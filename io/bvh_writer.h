// BVH writer: a Skeleton and a Motion to BVH text, the inverse of bvh_reader.h.
//
// Conventions (the reader's, see bvh_reader.h):
// - Lengths are written in the skeleton's units times BvhWriteOptions::scale (OFFSETs,
//   end-site offsets and position channels). Angles are written in degrees.
// - Channel layout: each joint's JointSpec::channels, so a file read and written again
//   keeps its layout. Three adjustments keep every pose representable:
//     * a joint with no channels gets "Zrotation Xrotation Yrotation", the root
//       "Xposition Yposition Zposition Zrotation Xrotation Yrotation";
//     * rotation channels are completed to three (missing axes appended after the last
//       rotation channel), and a joint with position channels only gets three rotation
//       channels after them;
//     * a joint whose translation differs from its OFFSET in some frame, on an axis that
//       has no position channel, gets all three position channels (in place of its
//       partial ones, else first), because position channels REPLACE the OFFSET.
//   BvhWriteOptions::euler_order, when set, replaces every joint's rotation order (the
//   rotation channels keep their slots in the list).
// - Euler angles come from EulerFromQuaternion in each joint's order and are then made
//   continuous over time: each frame picks, of the two equivalent triples (a, b, c) and
//   (a + 180, 180 - b, c + 180) shifted by multiples of 360, the one nearest the previous
//   frame's, so that 179 -> -179 does not jump. Angles can therefore leave (-180, 180],
//   but stay within [-360, 360]: an angle that would leave it wraps back into
//   [-180, 180] (a jump of 360 at most once per turn, rather than unbounded angles
//   that would lose significant digits).
//   Angles below 1e-9 degrees (rounding noise of the extraction) are written as 0.
// - Rest rotations (ASF skeletons; BVH has none) are folded into the local rotation:
//   the file's rotation of joint j is R_rest_j * R_j. Since a joint's offset is already
//   in its parent's frame and its children's offsets are in the frame after
//   R_rest_j * R_j, forward kinematics of the written file equals the model's exactly;
//   only the meaning of "zero angles" changes (it is no longer the ASF rest pose).
// - Joints are written depth-first from the root, children in index order, end sites
//   ("End Site") after a joint's child joints; the MOTION columns follow that order.
// - Numbers are printed with `precision` significant digits (shortest form, "%g"-like);
//   the frame time is printed exactly (shortest round-trip form), 1 / frame_rate.
//
// The output always reads back with ReadBvh: each channel value equals the original
// within the printed precision (angles as rotations, since a triple can wrap or be the
// other equivalent one).
#ifndef MOCAPSOLVE_IO_BVH_WRITER_H_
#define MOCAPSOLVE_IO_BVH_WRITER_H_

#include <optional>
#include <string>
#include <vector>

#include "kinematics/compact_motion.h"
#include "kinematics/motion.h"
#include "kinematics/rotation.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct BvhWriteOptions {
  int precision = 6;                      // Significant digits of every value, 1..17.
  std::optional<EulerOrder> euler_order;  // Overrides every joint's rotation order.
  double scale = 1.0;                     // Multiplies lengths (offsets, positions); > 0.
};

// Checks what the writer needs: options in range, the motion's poses sized for the
// skeleton with finite values, a positive frame rate, joint names that fit on one line.
Status CheckBvhWritable(const Skeleton& skeleton, const Motion& motion,
                        const BvhWriteOptions& options);

// The BVH text; "" if CheckBvhWritable fails (call it, or WriteBvh, to get the reason).
std::string FormatBvh(const Skeleton& skeleton, const Motion& motion,
                      const BvhWriteOptions& options = BvhWriteOptions());

// A long motion's BVH in pieces (a take written window by window, pipeline/take_windows.h):
// Start fixes the channels from the first piece (as FormatBvh from the whole motion),
// Header is the text through "Frame Time" for `frames` frames, and AppendFrames appends the
// MOTION lines of frames [first, first + count) of a piece, each frame's Euler angles
// continued from the last frame appended. FormatBvh is Start, Header and one AppendFrames
// of the whole motion. A later piece that moves a translation axis the first piece's
// channels lack is an error naming the joint.
class BvhPieceWriter {
 public:
  Status Start(const Skeleton& skeleton, const Motion& first_piece, const BvhWriteOptions& options = {});
  // The channels from the whole motion, compact (as FormatBvh from its ToMotion()); then
  // every piece appended is checked, the first too.
  Status Start(const Skeleton& skeleton, const CompactMotion& whole, const BvhWriteOptions& options = {});
  std::string Header(int frames, double frame_rate) const;
  Status AppendFrames(const Motion& piece, int first, int count, std::string* out);

 private:
  const Skeleton* skeleton_ = nullptr;
  BvhWriteOptions options_;
  std::vector<std::vector<Channel>> channels_;
  std::vector<EulerOrder> orders_;
  std::vector<int> joint_order_;
  std::vector<Eigen::Vector3d> previous_angles_;
  long long frames_written_ = 0;
  bool first_piece_checked_ = false;  // By Start(Motion).

  template <class Samples>
  void StartChannels(const Skeleton& skeleton, const Samples& motion, const BvhWriteOptions& options);
};

// Formats and writes through WriteFileAtomically (io/atomic_file.h).
Status WriteBvh(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                const BvhWriteOptions& options = BvhWriteOptions());
// The same bytes from a CompactMotion (kinematics/compact_motion.h), expanded and formatted
// a piece at a time into an AtomicFileWriter: a long take's text is never whole in memory.
Status WriteBvh(const std::string& path, const Skeleton& skeleton, const CompactMotion& motion,
                const BvhWriteOptions& options = BvhWriteOptions());

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_BVH_WRITER_H_
