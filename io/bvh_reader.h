// BVH (Biovision Hierarchy) reader: a HIERARCHY section (joints, offsets, channel
// layouts, end sites) into a Skeleton, and the MOTION section into a Motion.
//
// Conventions:
// - Lengths stay in the file's units (BVH does not say which): the skeleton's unit is
//   LengthUnit() ("unknown"). Angles in the file are degrees; the model holds unit
//   quaternions.
// - Rotation channels: a joint's rotation channels, in the order listed, name the
//   factors of an intrinsic product, so "Zrotation Xrotation Yrotation" with values
//   (a, b, c) is R = Rz(a) * Rx(b) * Ry(c) (EulerOrder::kZXY, kinematics/rotation.h). A
//   joint with one or two rotation channels gets the listed factors only; a joint with
//   none gets the identity. Any order is accepted, per joint.
// - Position channels REPLACE the joint's OFFSET: Pose::translations[j] holds the channel
//   values, and an axis without a channel keeps the OFFSET's component. A joint without
//   position channels has translations[j] = OFFSET in every frame. (The root OFFSET of
//   real files such as CMU 16_15 equals its first frame's position, which is only
//   consistent with "replace"; Blender's importer reads it the same way.) Translation is
//   applied before rotation, whatever the channel order: T(t_j) * R_j.
// - JointSpec::channels keeps each joint's channel list as in the file, so that the
//   writer (bvh_writer.h) can reproduce the layout.
// - End sites become EndSite entries named "<joint>_End" ("<joint>_End2", ... if a joint
//   has several).
// - Each joint's quaternion series is made sign-continuous (MakeSignContinuous).
// - Frame rate = 1 / "Frame Time:" (at least 1e-6 s: a smaller or denormal time is an
//   error, not an infinite rate). A skeleton nested deeper than kMaxSkeletonDepth is an error.
//
// Input: LF or CRLF line endings, spaces or tabs, a UTF-8 byte-order mark, numbers in
// fixed or scientific notation with an optional '+'. Keywords (HIERARCHY, ROOT, JOINT,
// OFFSET, CHANNELS, End Site, MOTION, Frames:, Frame Time:) are case-sensitive; channel
// names are not. A joint's name is the rest of its ROOT/JOINT line (it may hold spaces).
// Each frame of the MOTION section is one line holding exactly one value per channel;
// blank lines are skipped.
//
// Errors: anything malformed (truncated file, wrong value count, non-numeric or
// non-finite values, unknown channel names, a frame time below 1e-6 s, duplicate joint
// names, a repeated channel, unbalanced braces, ...) returns Status::Error with one
// line "NAME:LINE: expected X, got 'Y'". The reader never allocates more frames than the
// data present can hold, whatever "Frames:" declares, and refuses files whose motion
// would take more than 4 joint-frames per byte of input (only possible with many joints
// without channels; real files hold several bytes per joint-frame), so that no small
// input can make it allocate gigabytes.
#ifndef MOCAPSOLVE_IO_BVH_READER_H_
#define MOCAPSOLVE_IO_BVH_READER_H_

#include <string>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Reads the file at `path`; error messages name `path`. On error *skeleton and *motion
// are left unchanged.
Status ReadBvh(const std::string& path, Skeleton* skeleton, Motion* motion);

// Parses BVH text held in memory; error messages name `name_for_errors`.
Status ParseBvh(const std::string& text, const std::string& name_for_errors, Skeleton* skeleton,
                Motion* motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_BVH_READER_H_
