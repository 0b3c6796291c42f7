// Edit files: an artist's pose edits at one or more frames, as JSON, for `mocapsolve
// propagate` (problems/edit_propagation/pose_edit.h applies them, eqs. 4-5 of Dean, Lewis &
// Chalmers 2018).
//
// Format (keys in any order; unknown keys are an error so typos surface):
//   {
//     "format": "mocapsolve.edit",        optional; if present exactly this string
//     "version": 1,                       optional; if present 1
//     "comment": "...",                   optional, any string, ignored
//     "frame": 120,                       one edit: the edited frame (0-based integer)
//     "joints": {                         optional: joint name -> its offset
//       "lhumerus": {"rotation_offset_deg": [x, y, z]}
//     },
//     "root_translation_offset": [x, y, z]  optional, skeleton length units, world axes
//   }
// or, for several edited frames at once,
//   {"edits": [{"frame": 120, "joints": {...}, "root_translation_offset": [...]}, ...]}
// (then "frame", "joints" and "root_translation_offset" may not appear at the top level).
//
// A rotation offset is a rotation vector in degrees, a local increment in the joint's own
// frame: the edited rotation is R'_j = R_j exp(offset_j) (DESIGN.md's increment
// convention). Each edit must change something (a joint or the root translation); frames
// must be distinct. The frame is checked against the clip only by the caller (the file
// does not know the clip's length).
//
// Errors are one line naming the file, line:column and the field:
//   up.json:4:27: edits[1].joints.lhumerus.rotation_offset_deg: expected 3 numbers, got 2
//   up.json:3:13: joints: unknown joint 'lhumerous'
#ifndef MOCAPSOLVE_IO_EDIT_FILE_H_
#define MOCAPSOLVE_IO_EDIT_FILE_H_

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct EditFileEntry {
  int frame = -1;
  std::vector<std::pair<int, Eigen::Vector3d>> rotation_offsets_rad;  // (joint, radians).
  Eigen::Vector3d root_translation_offset = Eigen::Vector3d::Zero();
  std::string where;  // "FILE:LINE:COL" of the edit's "frame", for later messages.
};

// Reads an edit file against the skeleton whose joints it names.
Status ReadEditFile(const std::string& path, const Skeleton& skeleton,
                    std::vector<EditFileEntry>* edits);
// Parses edit JSON held in memory; file_name only labels error messages.
Status ParseEditFile(std::string_view text, const std::string& file_name, const Skeleton& skeleton,
                     std::vector<EditFileEntry>* edits);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_EDIT_FILE_H_
