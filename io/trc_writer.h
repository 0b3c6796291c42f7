// TRC writer: MarkerTrajectories to an OpenSim TRC file (layout in trc_reader.h).
//
// Header: DataRate = CameraRate = OrigDataRate = frame_rate, NumFrames, NumMarkers,
// Units = the trajectories' unit name (must be known), OrigDataStartFrame = first_frame,
// OrigNumFrames = NumFrames. Rows: Frame# = first_frame + f, Time = (Frame# - 1) /
// DataRate (frame 1 at time 0, as OpenSim's examples), then x y z per marker.
// Missing samples are three empty cells, never zeros. Labels are written raw (subject
// prefix included); they must be non-empty and free of tabs and line breaks. A valid
// sample exactly at (0,0,0) is written as zeros and so reads back as missing.
//
// Numbers: the shortest text that reads back as the same double, except when that
// text needs more than 9 significant digits and the value is exactly a float (data
// read from a float C3D: 617.24761962890625): then the float's shortest text
// ("617.2476"). So values parsed from decimal text (TRC input) round-trip exactly, and
// float data round-trips to float precision without 17-digit noise.
#ifndef MOCAPSOLVE_IO_TRC_WRITER_H_
#define MOCAPSOLVE_IO_TRC_WRITER_H_

#include <string>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Writes through WriteFileAtomically (a temporary file renamed over path).
Status WriteTrc(const std::string& path, const MarkerTrajectories& trajectories);

// Builds the text in memory; file_name goes into the PathFileType line and errors.
Status FormatTrc(const MarkerTrajectories& trajectories, const std::string& file_name,
                 std::string* text);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_TRC_WRITER_H_
