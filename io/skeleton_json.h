// A Skeleton (kinematics/skeleton.h) as a JSON object, for files that hold a fitted
// skeleton inline (subject files, pipeline/subject.h). Everything the Skeleton holds is
// written, so a skeleton read back equals the one written (offsets round-trip exact):
//   {
//     "units": "cm",                    the LengthUnit's name
//     "metres_per_unit": 0.01,          0 when the unit is unknown
//     "joints": [                       parents first (preorder), root first
//       {"name": "root",
//        "parent": null,                null for the root, else an earlier joint's name
//        "offset": [x, y, z],           in the parent's frame, `units`
//        "rest_rotation": [w, x, y, z], optional, unit quaternion (default identity)
//        "channels": ["Xposition", ...],        optional: the source file's channel layout
//        "rotation_axes": ["z", "y", "x"],      optional: the rotation dofs in product order
//        "rotation_limits": [[lo, hi], ...]}    optional, radians, one per rotation axis;
//     ],                                        null for an unbounded side
//     "end_sites": [{"name": "...", "parent": "joint", "offset": [x, y, z]}]   optional
//   }
// Unknown keys are errors; messages name the file, line:column and field, e.g.
//   s.json:12:19: skeleton.joints[3] 'lfemur': parent: unknown joint 'lhip'
#ifndef MOCAPSOLVE_IO_SKELETON_JSON_H_
#define MOCAPSOLVE_IO_SKELETON_JSON_H_

#include <string>

#include "io/json_reader.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// `field` prefixes messages ("skeleton"); file_name labels them.
Status InterpretSkeletonJson(const JsonNode& node, const std::string& file_name, const std::string& field,
                             Skeleton* skeleton);

// The object text (indented by `indent` spaces after each newline; one joint per line).
std::string FormatSkeletonJson(const Skeleton& skeleton, int indent = 2);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_SKELETON_JSON_H_
