#include "io/live_frame.h"

#include <cmath>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>

#include "io/json_reader.h"
#include "io/json_writer.h"
#include "kinematics/marker_trajectories.h"

namespace mocapsolve {
namespace {

std::string FramePrefix(long frame) { return frame >= 0 ? "frame " + std::to_string(frame) + ": " : ""; }

// A marker's value: [x, y, z] of finite numbers within the readers' bound, or null.
Status ParsePosition(const JsonNode& value, Eigen::Vector3d* position) {
  if (value.is_null()) {
    position->setConstant(std::numeric_limits<double>::quiet_NaN());
    return Status::Ok();
  }
  if (!value.is_array() || value.items.size() != 3) return Status::Error("expected [x, y, z] or null");
  for (int k = 0; k < 3; ++k) {
    const JsonNode& item = value.items[k];
    if (!item.is_number() || !std::isfinite(item.number) ||
        std::abs(item.number) > MarkerTrajectories::kMaxCoordinate) {
      return Status::Error("expected [x, y, z] (3 finite numbers, |value| <= 1e9)");
    }
    (*position)[k] = item.number;
  }
  return Status::Ok();
}

void AppendNumber(double value, std::string* out) {  // 10 significant digits, as %.10g.
  char text[32];
  const auto end = std::to_chars(text, text + sizeof(text), value, std::chars_format::general, 10).ptr;
  out->append(text, end);
}

void AppendBytes(const void* data, size_t size, std::string* out) {
  out->append(static_cast<const char*>(data), size);
}

template <class T>
T ReadLittle(const char* bytes) {  // The machines we build for are little-endian.
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

}  // namespace

Status ParseJsonFrameLine(std::string_view line, LiveFrame* frame) {
  frame->frame = -1;
  frame->time = -1.0;
  frame->labels.clear();
  frame->positions.clear();
  JsonNode root;
  Status status = ParseJson(line, "frame line", &root);
  if (!status.ok()) return Status::Error("malformed JSON: " + status.message());
  if (!root.is_object()) return Status::Error("a frame line must be a JSON object");
  if (const JsonNode* number = root.Find("frame"); number != nullptr && number->is_number() &&
                                                   number->number >= 0 && number->number < 9.0e15 &&
                                                   number->number == std::floor(number->number)) {
    frame->frame = static_cast<long>(number->number);
  } else {
    return Status::Error(std::string(number == nullptr ? "frame: missing" : "frame: expected an integer >= 0"));
  }
  const std::string where = FramePrefix(frame->frame);
  static const std::set<std::string> allowed = {"frame", "time", "markers", "points"};
  if (const auto* unknown = FindUnknownKey(root, allowed)) {
    return Status::Error(where + unknown->first + ": unknown key (" + KeyList(allowed) + ")");
  }
  if (const JsonNode* time = root.Find("time")) {
    if (!time->is_number() || !std::isfinite(time->number) || time->number < 0) {
      return Status::Error(where + "time: expected a number >= 0 (seconds)");
    }
    frame->time = time->number;
  }
  if (root.Find("points") != nullptr) {
    return Status::Error(where + "points: unlabelled points are not supported by live yet; label the stream "
                         "(markers: {label: [x, y, z]})");
  }
  const JsonNode* markers = root.Find("markers");
  if (markers == nullptr) return Status::Error(where + "markers: missing");
  if (!markers->is_object()) return Status::Error(where + "markers: expected an object {label: [x, y, z] | null}");
  frame->labels.reserve(markers->members.size());
  frame->positions.reserve(markers->members.size());
  for (const auto& [label, value] : markers->members) {
    Eigen::Vector3d position;
    status = ParsePosition(value, &position);
    if (!status.ok()) return Status::Error(where + "markers." + label + ": " + status.message());
    frame->labels.push_back(label);
    frame->positions.push_back(position);
  }
  return Status::Ok();
}

std::string FormatJsonFrameLine(const LiveFrame& frame) {
  std::string line = "{\"frame\": " + std::to_string(frame.frame);
  if (frame.time >= 0) {
    line += ", \"time\": ";
    AppendNumber(frame.time, &line);
  }
  line += ", \"markers\": {";
  for (size_t m = 0; m < frame.labels.size(); ++m) {
    line += (m == 0 ? "" : ", ") + JsonQuote(frame.labels[m]) + ": ";
    const Eigen::Vector3d& x = frame.positions[m];
    if (!x.allFinite()) {
      line += "null";
      continue;
    }
    line += "[";
    for (int k = 0; k < 3; ++k) {
      if (k > 0) line += ", ";
      AppendNumber(x[k], &line);
    }
    line += "]";
  }
  return line + "}}";
}

std::string FormatBinaryStreamHeader(const std::vector<std::string>& labels) {
  std::string out(kBinaryStreamMagic, 8);
  const uint32_t count = static_cast<uint32_t>(labels.size());
  AppendBytes(&count, 4, &out);
  for (const std::string& label : labels) {
    const uint8_t size = static_cast<uint8_t>(std::min<size_t>(label.size(), 255));
    AppendBytes(&size, 1, &out);
    out.append(label, 0, size);
  }
  return out;
}

std::string FormatBinaryFrame(const LiveFrame& frame) {
  std::string out(kBinaryFrameMagic, 4);
  const uint32_t number = static_cast<uint32_t>(frame.frame);
  const float time = static_cast<float>(frame.time);
  const uint32_t count = static_cast<uint32_t>(frame.positions.size());
  AppendBytes(&number, 4, &out);
  AppendBytes(&time, 4, &out);
  AppendBytes(&count, 4, &out);
  for (const Eigen::Vector3d& x : frame.positions) {
    const float xyz[3] = {static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2])};
    AppendBytes(xyz, sizeof(xyz), &out);
  }
  return out;
}

Status ParseBinaryFrameHeader(std::string_view bytes, size_t markers, LiveFrame* frame) {
  frame->frame = -1;
  frame->time = -1.0;
  if (bytes.size() != kBinaryFrameHeaderBytes || bytes.compare(0, 4, kBinaryFrameMagic) != 0) {
    return Status::Error("binary frame: expected the frame magic \"MSFR\" (the stream lost its framing)");
  }
  frame->frame = ReadLittle<uint32_t>(bytes.data() + 4);
  const float time = ReadLittle<float>(bytes.data() + 8);
  const uint32_t count = ReadLittle<uint32_t>(bytes.data() + 12);
  const std::string where = FramePrefix(frame->frame);
  if (count != markers) {
    return Status::Error(where + "count: " + std::to_string(count) + " markers, the stream header gave " +
                         std::to_string(markers));
  }
  if (!std::isfinite(time) || time < 0) return Status::Error(where + "time: expected a number >= 0 (seconds)");
  frame->time = time;
  frame->positions.resize(count);
  return Status::Ok();
}

Status ParseBinaryFramePositions(std::string_view bytes, LiveFrame* frame) {
  const size_t count = frame->positions.size();
  if (bytes.size() != count * 12) return Status::Error(FramePrefix(frame->frame) + "positions: truncated");
  for (size_t m = 0; m < count; ++m) {
    Eigen::Vector3d x;
    bool missing = false;
    for (int k = 0; k < 3; ++k) {
      const float value = ReadLittle<float>(bytes.data() + 12 * m + 4 * k);
      if (std::isnan(value)) missing = true;
      if (std::isinf(value) || std::abs(value) > MarkerTrajectories::kMaxCoordinate) {
        return Status::Error(FramePrefix(frame->frame) + "positions[" + std::to_string(m) +
                             "]: expected finite numbers (NaN = missing), |value| <= 1e9");
      }
      x[k] = value;
    }
    if (missing) x.setConstant(std::numeric_limits<double>::quiet_NaN());
    frame->positions[m] = x;
  }
  return Status::Ok();
}

}  // namespace mocapsolve
