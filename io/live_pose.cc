#include "io/live_pose.h"

#include <charconv>
#include <cstdio>

#include "io/bvh_writer.h"
#include "io/json_writer.h"

namespace mocapsolve {
namespace {

void Append(double value, std::string* out) {  // 9 significant digits, as %.9g.
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), value, std::chars_format::general, 9).ptr;
  out->append(text, end);
}

Motion OneFrame(const Pose& pose, double frame_rate) {
  Motion motion;
  motion.frame_rate = frame_rate > 0 ? frame_rate : 120.0;
  motion.frames.push_back(pose);
  return motion;
}

}  // namespace

std::string FormatLivePoseJson(const Skeleton& skeleton, const Pose& pose, const LivePoseLine& line) {
  std::string out;
  out.reserve(64 + 64 * skeleton.num_joints());
  out += "{\"frame\": " + std::to_string(line.frame) + ", \"time\": ";
  Append(line.time, &out);
  out += ", \"root\": [";
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out += ", ";
    Append(pose.translations[0][k], &out);
  }
  out += "], \"rotations\": {";
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const Eigen::Quaterniond& q = pose.rotations[j];
    out += (j == 0 ? "" : ", ") + JsonQuote(skeleton.name(j)) + ": [";
    Append(q.w(), &out), out += ", ", Append(q.x(), &out), out += ", ";
    Append(q.y(), &out), out += ", ", Append(q.z(), &out), out += "]";
  }
  out += "}, \"markers_used\": " + std::to_string(line.markers_used) +
         ", \"markers_predicted\": " + std::to_string(line.markers_predicted) + ", \"rms\": ";
  Append(line.rms, &out);
  out += "}\n";
  return out;
}

Status FormatLiveBvhHeader(const Skeleton& skeleton, const Pose& pose, double frame_rate, std::string* header) {
  const Motion motion = OneFrame(pose, frame_rate);
  Status status = CheckBvhWritable(skeleton, motion, BvhWriteOptions());
  if (!status.ok()) return status;
  const std::string text = FormatBvh(skeleton, motion);
  const size_t frames = text.find("\nFrames:");
  const size_t frame_time = text.find("Frame Time:", frames);
  const size_t end = text.find('\n', frame_time);
  if (frames == std::string::npos || frame_time == std::string::npos || end == std::string::npos) {
    return Status::Error("BVH header: unexpected writer output");  // A bug, not bad input.
  }
  *header = text.substr(0, frames + 1) + text.substr(frame_time, end + 1 - frame_time);
  return Status::Ok();
}

std::string FormatLiveBvhLine(const Skeleton& skeleton, const Pose& pose) {
  const std::string text = FormatBvh(skeleton, OneFrame(pose, 120.0));
  if (text.size() < 2) return "\n";
  const size_t start = text.rfind('\n', text.size() - 2);
  return text.substr(start + 1);
}

}  // namespace mocapsolve
