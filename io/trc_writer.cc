#include "io/trc_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

int SignificantDigits(const char* begin, const char* end) {
  int digits = 0;
  bool leading = true;
  for (const char* c = begin; c != end && *c != 'e'; ++c) {
    if (*c < '0' || *c > '9') continue;
    if (*c != '0') leading = false;
    if (!leading) ++digits;
  }
  return digits;
}

// See the header: the double's shortest text unless it is long and the value is
// exactly a float (then the float's shortest text, exact to float precision).
void AppendNumber(double value, std::string* out) {
  char buffer[64];
  const auto as_double = std::to_chars(buffer, buffer + sizeof buffer, value);
  const float as_float = static_cast<float>(value);
  if (SignificantDigits(buffer, as_double.ptr) > 9 && static_cast<double>(as_float) == value) {
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, as_float);
    out->append(buffer, result.ptr);
    return;
  }
  out->append(buffer, as_double.ptr);
}

std::string BaseName(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

Status FormatTrc(const MarkerTrajectories& trajectories, const std::string& file_name,
                 std::string* text) {
  const auto error = [&](const std::string& what) { return Status::Error(file_name + ": " + what); };
  if (!trajectories.unit.known()) {
    return error("unit " + QuoteToken(trajectories.unit.name) + " is unknown; TRC needs Units (mm, cm or m)");
  }
  if (Status s = CheckMarkerBounds(trajectories); !s.ok()) return error(s.message());  // io/input_limits.h
  for (int m = 0; m < trajectories.num_markers(); ++m) {
    const std::string& label = trajectories.label(m);
    if (label.empty() || label.find_first_of("\t\r\n") != std::string::npos ||
        label.find_first_not_of(' ') == std::string::npos) {
      return error("marker " + std::to_string(m) + " label '" + label +
                   "' is empty or holds a tab or line break");
    }
  }
  const int num_frames = trajectories.num_frames();
  const int num_markers = trajectories.num_markers();
  std::string out;
  std::string rate;
  AppendNumber(trajectories.frame_rate, &rate);
  out += "PathFileType\t4\t(X/Y/Z)\t" + BaseName(file_name) + "\n";
  out += "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame"
         "\tOrigNumFrames\n";
  out += rate + "\t" + rate + "\t" + std::to_string(num_frames) + "\t" +
         std::to_string(num_markers) + "\t" + trajectories.unit.name + "\t" + rate + "\t" +
         std::to_string(trajectories.first_frame) + "\t" + std::to_string(num_frames) + "\n";
  out += "Frame#\tTime";
  for (const std::string& label : trajectories.labels()) out += "\t" + label + "\t\t";
  out += "\n\t";
  for (int m = 1; m <= num_markers; ++m) {
    const std::string n = std::to_string(m);
    out += "\tX" + n + "\tY" + n + "\tZ" + n;
  }
  out += "\n\n";
  out.reserve(out.size() + static_cast<size_t>(num_frames) * (24 + 30 * static_cast<size_t>(num_markers)));
  for (int f = 0; f < num_frames; ++f) {
    const int frame_number = trajectories.first_frame + f;
    char time[32];
    std::snprintf(time, sizeof time, "%.10g", (frame_number - 1) / trajectories.frame_rate);
    out += std::to_string(frame_number);
    out += '\t';
    out += time;
    for (int m = 0; m < num_markers; ++m) {
      if (!trajectories.valid(f, m)) {
        out.append("\t\t\t", 3);
        continue;
      }
      const Eigen::Index i = trajectories.index(f, m);
      for (int k = 0; k < 3; ++k) {
        out += '\t';
        AppendNumber(trajectories.positions()(k, i), &out);
      }
    }
    out += '\n';
  }
  *text = std::move(out);
  return Status::Ok();
}

Status WriteTrc(const std::string& path, const MarkerTrajectories& trajectories) {
  std::string text;
  Status status = FormatTrc(trajectories, path, &text);
  if (!status.ok()) return status;
  return WriteFileAtomically(path, text);
}

}  // namespace mocapsolve
