// TRC reader: OpenSim / Motion Analysis marker files into MarkerTrajectories.
//
// Layout (tab-separated text, one frame per line):
//   1  PathFileType  4  (X/Y/Z)  <file name>
//   2  DataRate  CameraRate  NumFrames  NumMarkers  Units  OrigDataRate  ...   (keys)
//   3  60.00     60.00       151        41          mm     60.00         ...   (values)
//   4  Frame#  Time  <name 1>  <tab>  <tab>  <name 2>  ...   (one name per x,y,z triple)
//   5  <tab>  <tab>  X1  Y1  Z1  X2  ...
//   then (after optional blank lines) rows: Frame#  Time  x1  y1  z1  x2  ...
// Header values are matched by key name (any order, any case); DataRate, NumFrames,
// NumMarkers and Units are required. Units may be mm, cm or m (also spelled out), and
// positions are kept in that unit. Axes are the file's (OpenSim: Y-up).
//
// Rows: at least 2 + 3 x NumMarkers cells; extra cells must be empty (several writers
// end rows with a tab). Frame# and Time must be numbers; Time is not used (frame f is
// at (first_frame - 1 + f) / DataRate in the writer's convention). first_frame is the
// first row's Frame#. The number of rows must equal NumFrames.
//
// Missing samples (OpenSim practice): a marker whose x, y or z cell is empty (or NaN)
// is missing; so is a marker at exactly (0,0,0) (TrcReadOptions::zero_position_is_
// missing, default on), since several exporters write gaps as zeros (the Hamner
// running example's L.Bicep is all zeros).
//
// Errors name the file and line (and column or key); the reader never allocates more
// than the file's text justifies.
#ifndef MOCAPSOLVE_IO_TRC_READER_H_
#define MOCAPSOLVE_IO_TRC_READER_H_

#include <string>
#include <string_view>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct TrcReadOptions {
  // Read an exactly (0,0,0) marker as missing.
  bool zero_position_is_missing = true;
};

Status ReadTrc(const std::string& path, MarkerTrajectories* trajectories,
               const TrcReadOptions& options = {});

// Parses TRC text held in memory; file_name only labels error messages.
Status ParseTrc(std::string_view text, const std::string& file_name,
                MarkerTrajectories* trajectories, const TrcReadOptions& options = {});

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_TRC_READER_H_
