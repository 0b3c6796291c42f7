// What `mocapsolve live` writes per frame (docs/live.md):
//   json: one line per frame
//     {"frame": 12, "time": 0.1, "root": [x, y, z], "rotations": {"root": [w, x, y, z], ...},
//      "markers_used": 41, "markers_predicted": 0, "rms": 4.2}
//     root: the root joint's translation (skeleton units); rotations: every joint's local
//     rotation (unit quaternion w, x, y, z; the model's, after the skeleton's rest rotation
//     as kinematics/skeleton.h defines); rms: the frame's RMS marker residual in `rms_unit`.
//   bvh: the skeleton's BVH HIERARCHY once, then "MOTION" and "Frame Time: T" (no Frames
//     line: the count is not known until the stream ends), then one MOTION line per frame,
//     laid out as io/bvh_writer.h writes the first pose.
#ifndef MOCAPSOLVE_IO_LIVE_POSE_H_
#define MOCAPSOLVE_IO_LIVE_POSE_H_

#include <string>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct LivePoseLine {
  long frame = 0;
  double time = 0.0;
  int markers_used = 0;
  int markers_predicted = 0;
  double rms = 0.0;
};

// The JSON line (with its '\n').
std::string FormatLivePoseJson(const Skeleton& skeleton, const Pose& pose, const LivePoseLine& line);

// The BVH header for the skeleton and frame rate (rate <= 0: 120), laid out for `pose`.
Status FormatLiveBvhHeader(const Skeleton& skeleton, const Pose& pose, double frame_rate, std::string* header);
// One MOTION line (with its '\n').
std::string FormatLiveBvhLine(const Skeleton& skeleton, const Pose& pose);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_LIVE_POSE_H_
