// Acclaim AMC motion reader, for a skeleton read by ReadAsf (asf_reader.h states the
// Euler and kinematic conventions and the mapping into Skeleton).
//
// Format. '#' lines are comments (CMU files start with "#!OML:ASF <path>"). Header
// keywords before the first frame: ":FULLY-SPECIFIED", ":DEGREES" or ":RADIANS" (without
// either, the ASF's ':units angle' applies); other ':' keywords are ignored. Then
// frames: a line holding only the frame number (consecutive, any start; CMU starts at
// 1), followed by one line per bone, in any order: the bone name and one value per dof,
// in the ASF dof order ('root': one value per ':root order' entry, lengths in ASF units).
// Every bone with dofs must appear exactly once per frame; a bone without dofs may appear
// with no values. The frame rate is not in the file (CMU: 120 Hz).
//
// Pose of each frame (Motion frames in file order):
//   root:  translation = ASF root position + (TX, TY, TZ), rotation M_root from the
//          root's RX RY RZ in 'order' (first listed applied first);
//   bone:  translation = the skeleton's rest offset, rotation M_b = product of its dof
//          rotations, first listed applied first (AcclaimEulerRotation), missing dofs 0;
//          identity for bones without dofs.
// Rotation series are made sign-continuous (MakeSignContinuous).
//
// Errors are one line, "file:line: message"; a bone missing from a frame names the line
// of that frame's number.
#ifndef MOCAPSOLVE_IO_AMC_READER_H_
#define MOCAPSOLVE_IO_AMC_READER_H_

#include <string>

#include "io/asf_reader.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// `skeleton` and `info` from the same ReadAsf/ParseAsf call; frame_rate > 0 (CMU: 120).
// On error *motion is unspecified.
Status ReadAmc(const std::string& path, const Skeleton& skeleton, const AsfInfo& info,
               double frame_rate, Motion* motion);
// The same on text already in memory; name_for_errors prefixes the messages.
Status ParseAmc(const std::string& text, const std::string& name_for_errors,
                const Skeleton& skeleton, const AsfInfo& info, double frame_rate,
                Motion* motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_AMC_READER_H_
