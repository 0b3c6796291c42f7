// Marker set files: a MarkerSet (kinematics/marker_set.h, thesis eq. 9) as JSON.
//
//   x_m = sum_k w_mk * world_from_joint_{j_mk} * z_mk
//
// Format (version 2; keys in any order, unknown keys are an error so typos surface):
//   {
//     "format": "mocapsolve.markerset",          required, exactly this string
//     "version": 2,                              required, 1 or 2 (1: no solve_weight;
//                                                written as 1 when every weight is 1)
//     "units": "cm",                             required: the length unit of the offsets
//     "skeleton": "walk.bvh",                    optional, informative only
//     "markers": [                               required, may be empty
//       {"label": "LBWT",                        non-empty, unique (no subject prefix)
//        "attachments": [                        one or more
//          {"joint": "root",                     a joint name of the skeleton
//           "weight": 1.0,                       optional (default 1), in [0, 1e6]
//           "offset": [x, y, z]}],               z_mk in the joint's frame, `units`,
//                                                each within +-1e9
//        "solve_weight": 0.4}                    optional (default 1), in (0, 1e6]: the
//                                                marker's relative weight in a solve
//                                                (its learned tolerance, marker_weights.h)
//     ]
//   }
// Weights are renormalized to sum to 1 per marker (MarkerSet::Create); a marker on one
// bone has one attachment with weight 1.
//
// Units: offsets are meant in the skeleton's length unit, and WriteMarkerSet writes the
// skeleton's unit name. On read, "units" equal to the skeleton's unit name is taken as
// is; when both it and the skeleton's unit are known lengths ("mm", "cm", "m", "in", or
// an ASF "asf length L ..." unit) and differ, offsets are converted; when the skeleton's
// unit is unknown (BVH) the offsets are taken in skeleton units as they are; otherwise
// (an unknown or unrecognised file unit against a known skeleton unit) it is an error.
//
// Errors are one line naming the file, line:column, the marker and the field:
//   set.json:14:20: markers[3] 'LFWT': attachments[0].joint: unknown joint 'pelvis'
// Joints are written and read by name, so a file stays valid for any skeleton with the
// same joint names (e.g. the same character as BVH or ASF/AMC).
#ifndef MOCAPSOLVE_IO_MARKER_SET_FILE_H_
#define MOCAPSOLVE_IO_MARKER_SET_FILE_H_

#include <string>
#include <string_view>

#include "kinematics/marker_set.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Reads a marker set file against the skeleton whose joints it names.
Status ReadMarkerSet(const std::string& path, const Skeleton& skeleton, MarkerSet* marker_set);

// Parses marker set JSON held in memory; file_name only labels error messages.
Status ParseMarkerSet(std::string_view text, const std::string& file_name,
                      const Skeleton& skeleton, MarkerSet* marker_set);

// Interprets an already parsed marker set object (e.g. one held inline in a subject
// file, pipeline/subject.h); errors name file_name and the node's line:column.
class JsonNode;
Status InterpretMarkerSet(const JsonNode& root, const std::string& file_name, const Skeleton& skeleton,
                          MarkerSet* marker_set);

// Writes through WriteFileAtomically. skeleton_description goes into the informative
// "skeleton" field (omitted when empty). Offsets are printed round-trip exact.
Status WriteMarkerSet(const std::string& path, const Skeleton& skeleton,
                      const MarkerSet& marker_set, const std::string& skeleton_description = "");

// The file text WriteMarkerSet writes: one marker per line.
std::string FormatMarkerSet(const Skeleton& skeleton, const MarkerSet& marker_set,
                            const std::string& skeleton_description = "");

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MARKER_SET_FILE_H_
