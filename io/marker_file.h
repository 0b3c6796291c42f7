// Marker trajectory files by extension: .c3d or .trc (case-insensitive).
#ifndef MOCAPSOLVE_IO_MARKER_FILE_H_
#define MOCAPSOLVE_IO_MARKER_FILE_H_

#include <string>
#include <vector>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

// How marker files are read (C3D only; TRC files have none of these): see c3d_points.h.
struct MarkerReadOptions {
  bool include_model_outputs = false;  // C3dReadOptions::include_model_outputs.
  std::string subject_prefix;          // C3dReadOptions::subject_prefix.
  std::string preferred_subject_prefix;  // C3dReadOptions::preferred_subject_prefix.
  // Comma-separated labels whose every sample is read as missing; a label the file does
  // not have is an error naming it.
  std::string ignore_markers;
  // Receives the reader's warnings (duplicate labels renamed, model outputs set apart);
  // null: each is printed to stderr as "warning: ...".
  std::vector<std::string>* warnings = nullptr;
};

// The options ReadMarkerFile uses when given none: what the front end (apps/main.cc from
// --include_model_outputs and --subject_prefix) set before the command ran, so every
// command and library function that reads a marker file reads it the same way.
void SetDefaultMarkerReadOptions(const MarkerReadOptions& options);
const MarkerReadOptions& DefaultMarkerReadOptions();

Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories);
Status ReadMarkerFile(const std::string& path, MarkerTrajectories* trajectories,
                      const MarkerReadOptions& options);
// A take's size without its samples, for an estimate before any work: frames and marker
// labels (as ReadMarkerFile would read them, with the default read options). A C3D's
// header and parameters only (the file is read, its samples are not decoded); a TRC is
// read whole (its header's counts are not checked against its rows otherwise).
struct MarkerFileShape {
  int frames = 0;
  int markers = 0;
  double frame_rate = 0.0;
};
Status ReadMarkerFileShape(const std::string& path, MarkerFileShape* shape);

Status WriteMarkerFile(const std::string& path, const MarkerTrajectories& trajectories);
bool IsMarkerFile(const std::string& path);

// Commands and pipelines that compute on frames refuse a take without data, naming the
// file: 0 frames, 0 markers, or every sample missing (a 0-frame take crashed `repair` and
// `evaluate`, a take of 0 points and 2^31 - 1 frames `convert`, `corrupt` and `view`).
Status RequireMarkerData(const std::string& path, const MarkerTrajectories& trajectories);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MARKER_FILE_H_
