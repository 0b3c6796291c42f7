#include "io/bvh_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "kinematics/quote_token.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

// Seconds: 1e-6 (1 MHz) to 1000 (io/input_limits.h's frame rates).
constexpr double kMinFrameTime = 1.0 / kMaxFrameRate;
constexpr double kMaxFrameTime = 1.0 / kMinFrameRate;

// Whitespace within a line; '\n' ends a line and is handled separately so that line
// numbers stay right. '\r' is plain whitespace, which makes CRLF files read like LF ones.
inline bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
inline bool IsSpace(char c) { return IsBlank(c) || c == '\n'; }

// Parses a whole token as a finite double: fixed or scientific, optional leading '+'.
bool ParseFiniteDouble(std::string_view token, double* value) {
  const char* begin = token.data();
  const char* end = begin + token.size();
  // std::from_chars rejects a leading '+', which some exporters write.
  if (begin != end && *begin == '+' && end - begin > 1 && begin[1] != '-' && begin[1] != '+') {
    ++begin;
  }
  const auto [ptr, ec] = std::from_chars(begin, end, *value);
  return ec == std::errc() && ptr == end && std::isfinite(*value);
}

const char* const kChannelNames[] = {"Xposition", "Yposition", "Zposition",
                                     "Xrotation", "Yrotation", "Zrotation"};

bool ParseChannel(std::string_view token, Channel* channel) {
  for (int k = 0; k < 6; ++k) {
    const char* name = kChannelNames[k];
    if (token.size() != std::strlen(name)) continue;
    bool equal = true;
    for (size_t i = 0; i < token.size() && equal; ++i) {
      const char a = static_cast<char>(std::tolower(static_cast<unsigned char>(token[i])));
      const char b = static_cast<char>(std::tolower(static_cast<unsigned char>(name[i])));
      equal = a == b;
    }
    if (equal) {
      *channel = static_cast<Channel>(k);
      return true;
    }
  }
  return false;
}

bool IsRotation(Channel c) {
  return c == Channel::kXrotation || c == Channel::kYrotation || c == Channel::kZrotation;
}
int ChannelAxis(Channel c) { return static_cast<int>(c) % 3; }  // x, y, z = 0, 1, 2

// How one joint's values are laid out in a frame line, and where each goes.
struct JointLayout {
  int first_column = 0;
  int num_channels = 0;
  bool has_rotation = false;
  EulerOrder order = EulerOrder::kXYZ;
  // Per channel: 0..2 = translation axis, 3..5 = 3 + index of the angle in `order`.
  std::array<int8_t, 6> target{};
};

// The rotation order of a channel list: the listed rotation axes in order, completed with
// the missing ones (whose angles stay 0, so the completion does not change the rotation).
EulerOrder OrderFromChannels(const std::vector<Channel>& channels) {
  int axes[3];
  int count = 0;
  bool used[3] = {false, false, false};
  for (Channel c : channels) {
    if (IsRotation(c)) {
      axes[count++] = ChannelAxis(c);
      used[ChannelAxis(c)] = true;
    }
  }
  for (int a = 0; a < 3 && count < 3; ++a) {
    if (!used[a]) axes[count++] = a;
  }
  return EulerOrderFromAxes(axes[0], axes[1], axes[2]);
}

JointLayout MakeLayout(const std::vector<Channel>& channels, int first_column) {
  JointLayout layout;
  layout.first_column = first_column;
  layout.num_channels = static_cast<int>(channels.size());
  layout.order = OrderFromChannels(channels);
  for (size_t k = 0; k < channels.size(); ++k) {
    const int axis = ChannelAxis(channels[k]);
    if (IsRotation(channels[k])) {
      layout.has_rotation = true;
      int slot = 0;
      while (EulerAxis(layout.order, slot) != axis) ++slot;
      layout.target[k] = static_cast<int8_t>(3 + slot);
    } else {
      layout.target[k] = static_cast<int8_t>(axis);
    }
  }
  return layout;
}

class BvhParser {
 public:
  BvhParser(const std::string& text, const std::string& name)
      : begin_(text.data()), p_(text.data()), end_(text.data() + text.size()), name_(name) {}

  Status Parse(Skeleton* skeleton, Motion* motion);

 private:
  struct Token {
    std::string_view text;
    int line = 0;
    bool at_end() const { return text.empty(); }
  };
  // A ROOT/JOINT or End Site block whose '}' has not been seen yet.
  struct OpenBlock {
    bool end_site = false;
    int index = 0;  // Into joints_ or end_sites_.
    int line = 0;   // Of its ROOT/JOINT/End line.
    bool has_offset = false;
    bool has_channels = false;
  };

  Status ParseHierarchy();
  Status ParseJointHeader(const Token& keyword, int parent);
  Status ParseOffset(Eigen::Vector3d* offset);
  Status ParseChannels(std::vector<Channel>* channels);
  Status ParseMotion(Motion* motion);
  Status ParseFrameLine(const char* line_begin, const char* line_end, int line, int frame,
                        int num_columns, double* values);
  std::string ColumnWhere(int column) const;

  Token Next() {
    while (p_ < end_ && IsSpace(*p_)) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    Token token;
    token.line = p_ < end_ ? line_ : LastLine();
    const char* start = p_;
    while (p_ < end_ && !IsSpace(*p_)) ++p_;
    token.text = std::string_view(start, p_ - start);
    return token;
  }
  // Where "end of file" is reported: the last line, a final '\n' ending it rather than
  // starting another. Only valid once p_ has reached the end.
  int LastLine() const {
    return (end_ > begin_ && end_[-1] == '\n' && line_ > 1) ? line_ - 1 : line_;
  }
  // The rest of the current line, trimmed; leaves p_ at the line's '\n' (or the end).
  std::string_view RestOfLine() {
    while (p_ < end_ && IsBlank(*p_)) ++p_;
    const char* start = p_;
    while (p_ < end_ && *p_ != '\n') ++p_;
    const char* stop = p_;
    while (stop > start && IsBlank(stop[-1])) --stop;
    return std::string_view(start, stop - start);
  }

  Status Error(int line, const std::string& message) const {
    return Status::Error(name_ + ":" + std::to_string(line) + ": " + message);
  }
  Status Expected(const std::string& what, const Token& got) const {
    return Error(got.line, "expected " + what + ", got " +
                               (got.at_end() ? std::string("end of file") : QuoteToken(got.text)));
  }
  Status ExpectKeyword(const char* keyword) {
    const Token token = Next();
    if (token.text != keyword) return Expected(std::string("'") + keyword + "'", token);
    return Status::Ok();
  }
  std::string JointWhere(int joint) const { return "joint " + QuoteToken(joints_[joint].name); }

  const char* const begin_;
  const char* p_;
  const char* const end_;
  const std::string& name_;
  int line_ = 1;

  std::vector<JointSpec> joints_;
  std::vector<EndSite> end_sites_;
  std::vector<int> end_site_count_;           // Per joint, for "_End2" names.
  std::map<std::string, int> joint_name_line_;  // For duplicate-name messages.
  std::vector<OpenBlock> open_;
};

Status BvhParser::Parse(Skeleton* skeleton, Motion* motion) {
  // A UTF-8 byte-order mark, as some Windows exporters write.
  if (end_ - p_ >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) p_ += 3;
  if (Status s = ParseHierarchy(); !s.ok()) return s;
  Motion parsed;
  if (Status s = ParseMotion(&parsed); !s.ok()) return s;

  Skeleton built;
  if (Status s = Skeleton::Create(std::move(joints_), std::move(end_sites_), LengthUnit(), &built);
      !s.ok()) {
    return Status::Error(name_ + ": " + s.message());
  }
  MakeSignContinuous(&parsed);
  *skeleton = std::move(built);
  *motion = std::move(parsed);
  return Status::Ok();
}

Status BvhParser::ParseHierarchy() {
  if (Status s = ExpectKeyword("HIERARCHY"); !s.ok()) return s;
  const Token root = Next();
  if (root.text != "ROOT") return Expected("'ROOT'", root);
  if (Status s = ParseJointHeader(root, -1); !s.ok()) return s;

  // Iterative rather than recursive, so that absurd nesting cannot exhaust the stack.
  while (!open_.empty()) {
    OpenBlock& block = open_.back();
    const Token token = Next();
    // MOTION inside a block means a '}' is missing: say which block is still open.
    if (token.at_end() || token.text == "MOTION") {
      const std::string what = block.end_site
                                   ? "End Site of " + JointWhere(end_sites_[block.index].parent)
                                   : JointWhere(block.index);
      return Expected("'}' closing the " + what + " opened on line " +
                          std::to_string(block.line),
                      token);
    }
    if (token.text == "OFFSET") {
      if (block.has_offset) return Expected("one OFFSET per block", token);
      block.has_offset = true;
      Eigen::Vector3d* offset = block.end_site ? &end_sites_[block.index].offset
                                               : &joints_[block.index].offset;
      if (Status s = ParseOffset(offset); !s.ok()) return s;
    } else if (token.text == "}") {
      if (!block.has_offset) return Expected("OFFSET before '}'", token);
      open_.pop_back();
    } else if (block.end_site) {
      return Expected("OFFSET or '}' in End Site", token);
    } else if (token.text == "CHANNELS") {
      if (block.has_channels) return Expected("one CHANNELS per joint", token);
      block.has_channels = true;
      if (Status s = ParseChannels(&joints_[block.index].channels); !s.ok()) return s;
    } else if (token.text == "JOINT") {
      if (!block.has_offset) return Expected("OFFSET before the first child", token);
      if (Status s = ParseJointHeader(token, block.index); !s.ok()) return s;
    } else if (token.text == "End") {
      if (!block.has_offset) return Expected("OFFSET before the first child", token);
      const int parent = block.index;
      if (Status s = ExpectKeyword("Site"); !s.ok()) return s;
      if (Status s = ExpectKeyword("{"); !s.ok()) return s;
      const int count = ++end_site_count_[parent];
      EndSite site;
      site.name = joints_[parent].name + "_End" + (count > 1 ? std::to_string(count) : "");
      site.parent = parent;
      end_sites_.push_back(std::move(site));
      OpenBlock child;
      child.end_site = true;
      child.index = static_cast<int>(end_sites_.size()) - 1;
      child.line = token.line;
      open_.push_back(child);
    } else {
      return Expected("OFFSET, CHANNELS, JOINT, End Site or '}'", token);
    }
  }
  return Status::Ok();
}

// After ROOT/JOINT: the name (rest of the line) and '{'; pushes the new block.
Status BvhParser::ParseJointHeader(const Token& keyword, int parent) {
  std::string_view name = RestOfLine();
  bool brace_on_name_line = false;
  if (!name.empty() && name.back() == '{') {  // "JOINT Hips {"
    brace_on_name_line = true;
    name.remove_suffix(1);
    while (!name.empty() && IsBlank(name.back())) name.remove_suffix(1);
  }
  if (name.empty()) {
    return Error(keyword.line, "expected a joint name after " + std::string(keyword.text) +
                                   ", got end of line");
  }
  // Refused here, with the line, rather than later by Skeleton::Create.
  if (open_.size() > static_cast<size_t>(kMaxSkeletonDepth)) {
    return Error(keyword.line, "expected joints nested at most " +
                                   std::to_string(kMaxSkeletonDepth) + " deep, got deeper");
  }
  std::string joint_name(name);
  const auto [it, inserted] = joint_name_line_.emplace(joint_name, keyword.line);
  if (!inserted) {
    return Error(keyword.line, "expected a unique joint name, got " + QuoteToken(name) +
                                   " (already used on line " + std::to_string(it->second) + ")");
  }
  if (!brace_on_name_line) {
    if (Status s = ExpectKeyword("{"); !s.ok()) return s;
  }
  JointSpec spec;
  spec.name = std::move(joint_name);
  spec.parent = parent;
  joints_.push_back(std::move(spec));
  end_site_count_.push_back(0);
  OpenBlock block;
  block.index = static_cast<int>(joints_.size()) - 1;
  block.line = keyword.line;
  open_.push_back(block);
  return Status::Ok();
}

Status BvhParser::ParseOffset(Eigen::Vector3d* offset) {
  for (int i = 0; i < 3; ++i) {
    const Token token = Next();
    if (!ParseFiniteDouble(token.text, &(*offset)[i]) || !(std::abs((*offset)[i]) <= kMaxCoordinate)) {
      return Expected("a number within +-1e9 (OFFSET " + std::string(1, static_cast<char>('x' + i)) +
                          ")",
                      token);
    }
  }
  return Status::Ok();
}

Status BvhParser::ParseChannels(std::vector<Channel>* channels) {
  const Token count_token = Next();
  int count = -1;
  const char* count_end = count_token.text.data() + count_token.text.size();
  const auto [ptr, ec] = std::from_chars(count_token.text.data(), count_end, count);
  if (ec != std::errc() || ptr != count_end || count < 0 || count > 6) {
    return Expected("a channel count from 0 to 6", count_token);
  }
  for (int k = 0; k < count; ++k) {
    const Token token = Next();
    Channel channel;
    if (!ParseChannel(token.text, &channel)) {
      return Expected("a channel name (Xposition ... Zrotation)", token);
    }
    if (std::find(channels->begin(), channels->end(), channel) != channels->end()) {
      return Expected("each channel at most once per joint", token);
    }
    channels->push_back(channel);
  }
  return Status::Ok();
}

Status BvhParser::ParseMotion(Motion* motion) {
  const Token motion_token = Next();
  if (motion_token.text != "MOTION") {
    if (motion_token.text == "ROOT") {
      return Expected("MOTION (only one ROOT is supported)", motion_token);
    }
    return Expected("MOTION", motion_token);
  }
  const Token frames_token = Next();
  if (frames_token.text != "Frames:") return Expected("'Frames:'", frames_token);
  const Token count_token = Next();
  long long declared_frames = -1;
  {
    const char* stop = count_token.text.data() + count_token.text.size();
    const auto [ptr, ec] = std::from_chars(count_token.text.data(), stop, declared_frames);
    if (ec != std::errc() || ptr != stop || declared_frames < 0 || declared_frames > INT_MAX) {
      return Expected("a frame count", count_token);
    }
  }
  if (Status s = ExpectKeyword("Frame"); !s.ok()) return s;
  if (Status s = ExpectKeyword("Time:"); !s.ok()) return s;
  const Token time_token = Next();
  double frame_time = 0.0;
  // Below a microsecond (1e-320 parses as a finite denormal) the frame rate would be
  // absurd or infinite; above 1000 s (1e308) no writer can represent it.
  if (!ParseFiniteDouble(time_token.text, &frame_time) || !(frame_time >= kMinFrameTime) ||
      !(frame_time <= kMaxFrameTime)) {
    return Expected("a frame time of 1e-6 to 1000 seconds", time_token);
  }
  {
    const std::string_view rest = RestOfLine();
    if (!rest.empty()) {
      return Error(time_token.line, "expected end of line after the frame time, got " +
                                        QuoteToken(rest));
    }
  }
  motion->frame_rate = 1.0 / frame_time;

  // Column layout of a frame line.
  std::vector<JointLayout> layouts;
  layouts.reserve(joints_.size());
  int num_columns = 0;
  for (const JointSpec& spec : joints_) {
    layouts.push_back(MakeLayout(spec.channels, num_columns));
    num_columns += static_cast<int>(spec.channels.size());
  }
  const int num_frames = static_cast<int>(declared_frames);
  if (num_columns == 0 && num_frames > 0) {
    return Error(frames_token.line, "expected CHANNELS on at least one joint, got none for " +
                                        std::to_string(num_frames) + " frames");
  }

  // Each value takes at least two bytes (a digit and a separator), so the data present
  // bounds the frames worth reserving, whatever the header declares.
  const size_t bytes_left = static_cast<size_t>(end_ - p_);
  const size_t fit = num_columns > 0 ? bytes_left / (2 * static_cast<size_t>(num_columns)) + 1 : 0;
  // A pose costs ~56 bytes per joint, channels or not, so a small file declaring many
  // joints without channels and many short frame lines could still ask for gigabytes.
  // Real files spend several bytes per joint and frame (at least 2 with one channel
  // each); allow kMaxJointFramesPerByte per byte of input.
  constexpr size_t kMaxJointFramesPerByte = 4;
  const size_t num_joints_size = std::max<size_t>(joints_.size(), 1);
  const size_t max_frames =
      kMaxJointFramesPerByte * static_cast<size_t>(end_ - begin_) / num_joints_size;
  motion->frames.reserve(std::min({static_cast<size_t>(num_frames), fit, max_frames}));

  const int num_joints = static_cast<int>(joints_.size());
  std::vector<double> values(num_columns);
  int line = line_;
  int frame = 0;
  while (frame < num_frames) {
    // p_ is at a '\n' (or the end): step onto the next line.
    if (p_ < end_) {
      ++p_;
      ++line;
    }
    if (p_ >= end_) {
      line_ = line;
      return Error(LastLine(), "expected frame " + std::to_string(frame + 1) + " of " +
                             std::to_string(num_frames) + " (" + std::to_string(num_columns) +
                             " values), got end of file");
    }
    const char* line_begin = p_;
    const char* line_end =
        static_cast<const char*>(std::memchr(p_, '\n', static_cast<size_t>(end_ - p_)));
    if (line_end == nullptr) line_end = end_;
    p_ = line_end;
    const char* q = line_begin;
    while (q < line_end && IsBlank(*q)) ++q;
    if (q == line_end) continue;  // Blank line.
    if (static_cast<size_t>(frame) >= max_frames) {
      return Error(line, "expected at most " + std::to_string(max_frames) + " frames of " +
                             std::to_string(joints_.size()) + " joints in a " +
                             std::to_string(end_ - begin_) +
                             "-byte file (too many joints without channels), got more");
    }
    if (Status s = ParseFrameLine(line_begin, line_end, line, frame, num_columns, values.data());
        !s.ok()) {
      return s;
    }

    Pose pose;
    pose.translations.resize(num_joints);
    pose.rotations.resize(num_joints);
    for (int j = 0; j < num_joints; ++j) {
      const JointLayout& layout = layouts[j];
      Eigen::Vector3d translation = joints_[j].offset;
      Eigen::Vector3d angles_rad = Eigen::Vector3d::Zero();
      const double* v = values.data() + layout.first_column;
      for (int k = 0; k < layout.num_channels; ++k) {
        const int target = layout.target[k];
        if (target < 3) {
          translation[target] = v[k];
        } else {
          angles_rad[target - 3] = DegToRad(v[k]);
        }
      }
      pose.translations[j] = translation;
      pose.rotations[j] = layout.has_rotation ? QuaternionFromEuler(angles_rad, layout.order)
                                              : Eigen::Quaterniond::Identity();
    }
    motion->frames.push_back(std::move(pose));
    ++frame;
  }
  line_ = line;

  // Only whitespace may follow the last frame.
  const Token extra = Next();
  if (!extra.at_end()) {
    return Expected("end of file after " + std::to_string(num_frames) + " frames", extra);
  }
  return Status::Ok();
}

// One frame line into values[0, num_columns); the message names the frame and, for a
// bad value, its joint and channel.
Status BvhParser::ParseFrameLine(const char* line_begin, const char* line_end, int line,
                                 int frame, int num_columns, double* values) {
  const char* p = line_begin;
  int count = 0;
  while (true) {
    while (p < line_end && IsBlank(*p)) ++p;
    if (p == line_end) break;
    const char* token_begin = p;
    if (count == num_columns) {  // Too many: count them all for the message.
      int total = count;
      while (p < line_end) {
        while (p < line_end && !IsBlank(*p)) ++p;
        ++total;
        while (p < line_end && IsBlank(*p)) ++p;
      }
      return Error(line, "expected " + std::to_string(num_columns) + " values in frame " +
                             std::to_string(frame + 1) + ", got " + std::to_string(total));
    }
    // std::from_chars rejects a leading '+', which some exporters write.
    if (*p == '+' && p + 1 < line_end && (p[1] == '.' || (p[1] >= '0' && p[1] <= '9'))) ++p;
    double& value = values[count];
    const auto [ptr, ec] = std::from_chars(p, line_end, value);
    // Positions (and angles) beyond io/input_limits.h's kMaxCoordinate: a root at 1e308
    // was accepted, and `markers` wrote the frame as missing.
    if (ec != std::errc() || (ptr < line_end && !IsBlank(*ptr)) || !(std::abs(value) <= kMaxCoordinate)) {
      const char* token_end = token_begin;
      while (token_end < line_end && !IsBlank(*token_end)) ++token_end;
      return Error(line, "expected a number within +-1e9 (frame " + std::to_string(frame + 1) +
                             ", " + ColumnWhere(count) + "), got " +
                             QuoteToken(std::string_view(token_begin, token_end - token_begin)));
    }
    p = ptr;
    ++count;
  }
  if (count != num_columns) {
    return Error(line, "expected " + std::to_string(num_columns) + " values in frame " +
                           std::to_string(frame + 1) + ", got " + std::to_string(count));
  }
  return Status::Ok();
}

// "joint 'LeftHip' Zrotation" for a column of a frame line.
std::string BvhParser::ColumnWhere(int column) const {
  for (const JointSpec& spec : joints_) {
    const int n = static_cast<int>(spec.channels.size());
    if (column < n) {
      return "joint " + QuoteToken(spec.name) + " " + kChannelNames[static_cast<int>(spec.channels[column])];
    }
    column -= n;
  }
  return "column " + std::to_string(column);
}

}  // namespace

Status ParseBvh(const std::string& text, const std::string& name_for_errors, Skeleton* skeleton,
                Motion* motion) {
  BvhParser parser(text, name_for_errors);
  return parser.Parse(skeleton, motion);
}

Status ReadBvh(const std::string& path, Skeleton* skeleton, Motion* motion) {
  std::string text;
  if (Status s = ReadFileToString(path, &text); !s.ok()) return s;
  return ParseBvh(text, path, skeleton, motion);
}

}  // namespace mocapsolve
