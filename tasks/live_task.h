// `live` as one function: frames from a LiveFrameSource (io/live_source.h: stdin, a TCP
// client or a replayed file) are mapped onto the subject's marker set (labels matched
// with or without a subject prefix; the subject's axes; its marker scale, else the
// source's unit or --stream_units), tracked (problems/marker_solve/live_tracker.h: no
// look-ahead, missing markers predicted) and written through `write` as they arrive, as
// JSON lines or BVH MOTION lines (io/live_pose.h). Latency is measured per frame on the
// steady clock, from the frame's arrival to its pose written.
//
// A frame that cannot be read stops the run with its message (on_bad_frame=stop) or is
// reported through `warning` and counted as dropped (skip). An input that closes or stalls
// ends the run cleanly; an output that fails (a client gone) is an error. Poses written
// before an error stay written.
#ifndef MOCAPSOLVE_TASKS_LIVE_TASK_H_
#define MOCAPSOLVE_TASKS_LIVE_TASK_H_

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "io/json_writer.h"
#include "io/live_source.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "settings/live_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct LiveConfig {
  SolverSettings solver;
  LiveSettings live;
};

struct LiveIo {
  LiveFrameSource* source = nullptr;
  std::function<Status(std::string_view bytes)> write;  // The sink; an error ends the run.
  std::function<void(const std::string&)> warning;      // Skipped frames (may be empty).
};

struct LiveResult {
  long frames_in = 0;       // Frames received (read or not).
  long frames_out = 0;      // Poses written.
  long frames_dropped = 0;  // Bad frames skipped, plus frames a replay skipped to keep up.
  long bad_frames = 0;
  long unsolved_frames = 0;     // Pose kept from the previous frame.
  long predicted_samples = 0;   // Marker samples predicted.
  std::string end;              // "closed" (the input ended) or "stalled".
  std::vector<double> latency_ms;  // Per pose written.
  JsonObject report;            // What --report records (latency in ms, residuals in mm).
};

Status RunLive(const Subject& subject, const LiveConfig& config, const LiveIo& io, LiveResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_LIVE_TASK_H_
