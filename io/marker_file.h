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

// Commands and pipelines that compute on frames refuse a take without data, naming the
// file: 0 frames, 0 markers, or every sample missing (a 0-frame take crashed `repair` and
// `evaluate`, a take of 0 points and 2^31 - 1 frames `convert`, `corrupt` and `view`).
Status RequireMarkerData(const std::string& path, const MarkerTrajectories& trajectories);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MARKER_FILE_H_
