// C3D writer: MarkerTrajectories to a C3D file (the reader's counterpart, c3d_reader.h).
//
// Always Intel (processor 84, little-endian IEEE) with float storage (negative
// POINT:SCALE) and no analog data. Layout: header block, parameter section from block
// 2 (groups POINT, ANALOG, TRIAL, MANUFACTURER and, when the trajectories carry subject
// prefixes, SUBJECTS), then the frames from POINT:DATA_START, padded to a whole block.
//
// What is kept:
//   labels       POINT:LABELS, then LABELS2, LABELS3, ... when there are more than 255
//                points (or the labels are long; each parameter stays < 32 KB); blank
//                padded to the longest label. An empty label reads back as "*<n>".
//   rate, units  POINT:RATE (float), POINT:UNITS (omitted when the unit is unknown).
//   first frame  header words 4-5 and TRIAL:ACTUAL_START_FIELD/ACTUAL_END_FIELD (32-bit,
//                so frame numbers above 65535 survive).
//   residuals    the residual word, as the float of an int16: camera mask << 8 |
//                round(residual / |POINT:SCALE|). |POINT:SCALE| is chosen as
//                max(largest |coordinate| / 32000, largest residual / 255) so that no
//                residual saturates and an int16 conversion of the file would not
//                overflow; residuals thus come back within |POINT:SCALE| / 2.
//   model outputs  MarkerTrajectories::model_outputs (read from a C3D, c3d_points.h) are
//                written after the markers, unchanged (not rescaled or rotated), and listed
//                again in POINT:ANGLES, FORCES, ... so they read back as model outputs.
//                When their frame count is not the markers' (a cut take) they are left out.
//   missing      coordinates 0 and residual word -1, so every C3D reader sees an invalid
//                sample; missing samples are never written as real zeros.
// Caveat: a *valid* sample exactly at (0,0,0) is written as such, and readers that treat
// all-zero samples as gaps (ours by default) will read it back as missing.
//
// Coordinates are stored as float: they come back within float precision (relative
// 6e-8). A coordinate outside float range is an error.
#ifndef MOCAPSOLVE_IO_C3D_WRITER_H_
#define MOCAPSOLVE_IO_C3D_WRITER_H_

#include <string>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Writes through WriteFileAtomically (a temporary file renamed over path).
Status WriteC3d(const std::string& path, const MarkerTrajectories& trajectories);

// Builds the file image in memory; file_name only labels error messages.
Status EncodeC3d(const MarkerTrajectories& trajectories, const std::string& file_name,
                 std::string* bytes);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_C3D_WRITER_H_
