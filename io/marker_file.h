// Marker trajectory files by extension: .c3d or .trc (case-insensitive).
#ifndef MOCAPSOLVE_IO_MARKER_FILE_H_
#define MOCAPSOLVE_IO_MARKER_FILE_H_

#include <string>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories);
Status WriteMarkerFile(const std::string& path, const MarkerTrajectories& trajectories);
bool IsMarkerFile(const std::string& path);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MARKER_FILE_H_
