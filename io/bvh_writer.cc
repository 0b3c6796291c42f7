#include "io/bvh_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "io/motion_samples.h"

namespace mocapsolve {
namespace {

// Angles below this are written as 0 (see the header).
constexpr double kNoiseDegrees = 1e-9;

bool IsPosition(Channel c) {
  return c == Channel::kXposition || c == Channel::kYposition || c == Channel::kZposition;
}
int ChannelAxis(Channel c) { return static_cast<int>(c) % 3; }  // x, y, z = 0, 1, 2
Channel RotationChannel(int axis) { return static_cast<Channel>(3 + axis); }

const char* ChannelName(Channel c) {
  static const char* const kNames[] = {"Xposition", "Yposition", "Zposition",
                                       "Xrotation", "Yrotation", "Zrotation"};
  return kNames[static_cast<int>(c)];
}

// %g-like with `precision` significant digits; -0 is written as 0.
void AppendNumber(double value, int precision, std::string* out) {
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value + 0.0, std::chars_format::general,
                    precision);
  out->append(buffer, result.ptr);
}

// True if the translation of `joint` differs from its offset on `axis` in some frame.
// Exact comparison: the reader copies the offset bit for bit into unanimated axes, and
// anything else is real motion that must not be dropped.
// Samples: MotionSamples or CompactSamples (io/motion_samples.h).
template <class Samples>
bool AxisAnimated(const Skeleton& skeleton, const Samples& motion, int joint, int axis) {
  const double rest = skeleton.offset(joint)[axis];
  for (int f = 0; f < motion.num_frames(); ++f) {
    if (motion.translation(f, joint)[axis] != rest) return true;
  }
  return false;
}

// The channel list written for `joint` (see the header for the rules).
template <class Samples>
std::vector<Channel> OutputChannels(const Skeleton& skeleton, const Samples& motion, int joint,
                                    const std::optional<EulerOrder>& euler_order) {
  std::vector<Channel> channels = skeleton.joint(joint).channels;
  if (channels.empty()) {
    if (joint == 0) {
      channels = {Channel::kXposition, Channel::kYposition, Channel::kZposition};
    }
    channels.insert(channels.end(),
                    {Channel::kZrotation, Channel::kXrotation, Channel::kYrotation});
  }

  // Positions: all three if some unlisted axis is animated.
  bool listed[3] = {false, false, false};
  for (Channel c : channels) {
    if (IsPosition(c)) listed[ChannelAxis(c)] = true;
  }
  bool need_all_positions = false;
  for (int axis = 0; axis < 3; ++axis) {
    need_all_positions |= !listed[axis] && AxisAnimated(skeleton, motion, joint, axis);
  }
  if (need_all_positions) {
    const auto first = std::find_if(channels.begin(), channels.end(), IsPosition);
    const size_t insert_at = first == channels.end() ? 0 : first - channels.begin();
    channels.erase(std::remove_if(channels.begin(), channels.end(), IsPosition), channels.end());
    channels.insert(channels.begin() + insert_at,
                    {Channel::kXposition, Channel::kYposition, Channel::kZposition});
  }

  // Rotations: complete to three, missing axes after the last listed one.
  bool rotation_listed[3] = {false, false, false};
  size_t insert_at = channels.size();
  bool any_rotation = false;
  for (size_t k = 0; k < channels.size(); ++k) {
    if (!IsPosition(channels[k])) {
      rotation_listed[ChannelAxis(channels[k])] = true;
      insert_at = k + 1;
      any_rotation = true;
    }
  }
  if (!any_rotation) insert_at = channels.size();
  for (int axis = 0; axis < 3; ++axis) {
    if (!rotation_listed[axis]) {
      channels.insert(channels.begin() + insert_at, RotationChannel(axis));
      ++insert_at;
    }
  }

  if (euler_order.has_value()) {
    int slot = 0;
    for (Channel& c : channels) {
      if (!IsPosition(c)) c = RotationChannel(EulerAxis(*euler_order, slot++));
    }
  }
  return channels;
}

EulerOrder RotationOrder(const std::vector<Channel>& channels) {
  int axes[3];
  int count = 0;
  for (Channel c : channels) {
    if (!IsPosition(c)) axes[count++] = ChannelAxis(c);
  }
  return EulerOrderFromAxes(axes[0], axes[1], axes[2]);
}

// Of the two Euler triples of one rotation, (a, b, c) and (a + pi, pi - b, c + pi), each
// shifted componentwise by multiples of 2 pi, the one nearest `previous`; a component
// that would leave [-2 pi, 2 pi] is wrapped back into [-pi, pi] instead. Unbounded
// unwrapping would let angles grow without limit near gimbal lock, where the outer
// angles spin (CMU 16_15's feet reach 1225 degrees), and cost significant digits.
Eigen::Vector3d NearestEquivalentEuler(const Eigen::Vector3d& angles,
                                       const Eigen::Vector3d& previous) {
  const Eigen::Vector3d candidates[2] = {
      angles, Eigen::Vector3d(angles[0] + kPi, kPi - angles[1], angles[2] + kPi)};
  Eigen::Vector3d best = angles;
  double best_distance = INFINITY;
  for (Eigen::Vector3d candidate : candidates) {
    for (int k = 0; k < 3; ++k) {
      candidate[k] += 2.0 * kPi * std::round((previous[k] - candidate[k]) / (2.0 * kPi));
      if (std::abs(candidate[k]) > 2.0 * kPi) {
        candidate[k] = std::remainder(candidate[k], 2.0 * kPi);
      }
    }
    const double distance = (candidate - previous).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

// Joints depth-first from the root, children in index order.
std::vector<int> DepthFirstOrder(const Skeleton& skeleton,
                                 const std::vector<std::vector<int>>& children) {
  std::vector<int> order;
  order.reserve(skeleton.num_joints());
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const int j = stack.back();
    stack.pop_back();
    order.push_back(j);
    for (auto it = children[j].rbegin(); it != children[j].rend(); ++it) stack.push_back(*it);
  }
  return order;
}

class HierarchyWriter {
 public:
  HierarchyWriter(const Skeleton& skeleton, const std::vector<std::vector<Channel>>& channels,
                  const BvhWriteOptions& options, std::string* out)
      : skeleton_(skeleton), channels_(channels), options_(options), out_(out),
        children_(skeleton.num_joints()), end_sites_(skeleton.num_joints()) {
    for (int j = 1; j < skeleton.num_joints(); ++j) children_[skeleton.parent(j)].push_back(j);
    for (size_t e = 0; e < skeleton.end_sites().size(); ++e) {
      end_sites_[skeleton.end_sites()[e].parent].push_back(static_cast<int>(e));
    }
  }

  const std::vector<std::vector<int>>& children() const { return children_; }

  // Iterative so that a deep chain cannot exhaust the stack.
  void Write() {
    *out_ += "HIERARCHY\n";
    struct Frame {
      int joint;
      size_t next_child;
    };
    std::vector<Frame> stack;
    OpenJoint(0, 0);
    stack.push_back({0, 0});
    while (!stack.empty()) {
      Frame& top = stack.back();
      const int depth = static_cast<int>(stack.size());
      if (top.next_child < children_[top.joint].size()) {
        const int child = children_[top.joint][top.next_child++];
        OpenJoint(child, depth);
        stack.push_back({child, 0});
        continue;
      }
      for (int e : end_sites_[top.joint]) WriteEndSite(skeleton_.end_sites()[e], depth);
      Indent(depth - 1);
      *out_ += "}\n";
      stack.pop_back();
    }
  }

 private:
  // Indentation stops growing 32 levels deep, so that the text stays linear in the joint
  // count even for a skeleton nested kMaxSkeletonDepth deep (indentation is cosmetic).
  void Indent(int depth) { out_->append(static_cast<size_t>(std::min(depth, 32)), '\t'); }
  void AppendVector(const Eigen::Vector3d& v) {
    for (int i = 0; i < 3; ++i) {
      *out_ += ' ';
      AppendNumber(v[i] * options_.scale, options_.precision, out_);
    }
  }
  void OpenJoint(int j, int depth) {
    Indent(depth);
    *out_ += j == 0 ? "ROOT " : "JOINT ";
    *out_ += skeleton_.name(j);
    *out_ += '\n';
    Indent(depth);
    *out_ += "{\n";
    Indent(depth + 1);
    *out_ += "OFFSET";
    AppendVector(skeleton_.offset(j));
    *out_ += '\n';
    Indent(depth + 1);
    *out_ += "CHANNELS ";
    *out_ += std::to_string(channels_[j].size());
    for (Channel c : channels_[j]) {
      *out_ += ' ';
      *out_ += ChannelName(c);
    }
    *out_ += '\n';
  }
  void WriteEndSite(const EndSite& site, int depth) {
    Indent(depth);
    *out_ += "End Site\n";
    Indent(depth);
    *out_ += "{\n";
    Indent(depth + 1);
    *out_ += "OFFSET";
    AppendVector(site.offset);
    *out_ += '\n';
    Indent(depth);
    *out_ += "}\n";
  }

  const Skeleton& skeleton_;
  const std::vector<std::vector<Channel>>& channels_;
  const BvhWriteOptions& options_;
  std::string* out_;
  std::vector<std::vector<int>> children_;
  std::vector<std::vector<int>> end_sites_;
};

}  // namespace

Status CheckBvhWritable(const Skeleton& skeleton, const Motion& motion,
                        const BvhWriteOptions& options) {
  if (options.precision < 1 || options.precision > 17) {
    return Status::Error("BVH precision must be 1..17 significant digits, got " +
                         std::to_string(options.precision));
  }
  if (!(options.scale > 0.0) || !std::isfinite(options.scale)) {
    return Status::Error("BVH scale must be positive and finite, got " +
                         std::to_string(options.scale));
  }
  if (skeleton.num_joints() == 0) return Status::Error("cannot write BVH: skeleton has no joints");
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const std::string& name = skeleton.name(j);
    const bool control = std::any_of(name.begin(), name.end(), [](char c) {
      return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    });
    // The reader takes the rest of the ROOT/JOINT line, trimmed, as the name.
    if (name.empty() || control || name.front() == ' ' || name.back() == ' ' ||
        name.back() == '{') {
      return Status::Error("cannot write BVH: joint " + std::to_string(j) + " name '" + name +
                           "' does not fit on a BVH line (control characters, edge blanks or "
                           "a trailing '{')");
    }
  }
  if (Status s = ValidateMotion(skeleton, motion); !s.ok()) {
    return Status::Error("cannot write BVH: " + s.message());
  }
  // What the readers accept (io/input_limits.h): the frame time 1 / rate, and lengths
  // times scale (a frame time of 1e308 was written as a rate of 0).
  if (Status s = CheckMotionBounds(skeleton, motion, options.scale); !s.ok()) {
    return Status::Error("cannot write BVH: " + s.message());
  }
  double largest = 0.0;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    largest = std::max(largest, skeleton.offset(j).cwiseAbs().maxCoeff());
  }
  for (const EndSite& site : skeleton.end_sites()) {
    largest = std::max(largest, site.offset.cwiseAbs().maxCoeff());
  }
  for (const Pose& pose : motion.frames) {
    for (const Eigen::Vector3d& t : pose.translations) {
      largest = std::max(largest, t.cwiseAbs().maxCoeff());
    }
  }
  if (!std::isfinite(largest * options.scale)) {
    return Status::Error("cannot write BVH: lengths times scale " + std::to_string(options.scale) +
                         " overflow");
  }
  return Status::Ok();
}

Status BvhPieceWriter::Start(const Skeleton& skeleton, const Motion& first_piece, const BvhWriteOptions& options) {
  Status status = CheckBvhWritable(skeleton, first_piece, options);
  if (!status.ok()) return status;
  StartChannels(skeleton, MotionSamples(first_piece), options);
  first_piece_checked_ = true;
  return Status::Ok();
}

Status BvhPieceWriter::Start(const Skeleton& skeleton, const CompactMotion& whole, const BvhWriteOptions& options) {
  if (whole.empty()) return Status::Error("cannot write BVH: the motion has no frames");
  Motion first;  // The checks of the skeleton and options; every piece's own in AppendFrames.
  first.frame_rate = whole.frame_rate();
  first.frames.push_back(whole.Frame(0));
  Status status = CheckBvhWritable(skeleton, first, options);
  if (!status.ok()) return status;
  StartChannels(skeleton, CompactSamples(whole), options);
  first_piece_checked_ = false;
  return Status::Ok();
}

template <class Samples>
void BvhPieceWriter::StartChannels(const Skeleton& skeleton, const Samples& motion, const BvhWriteOptions& options) {
  skeleton_ = &skeleton;
  options_ = options;
  const int num_joints = skeleton.num_joints();
  channels_.assign(num_joints, {});
  orders_.assign(num_joints, EulerOrder());
  for (int j = 0; j < num_joints; ++j) {
    channels_[j] = OutputChannels(skeleton, motion, j, options.euler_order);
    orders_[j] = RotationOrder(channels_[j]);
  }
  std::string none;
  HierarchyWriter hierarchy(skeleton, channels_, options_, &none);
  joint_order_ = DepthFirstOrder(skeleton, hierarchy.children());
  previous_angles_.assign(num_joints, Eigen::Vector3d::Zero());
  frames_written_ = 0;
}

std::string BvhPieceWriter::Header(int frames, double frame_rate) const {
  std::string out;
  HierarchyWriter hierarchy(*skeleton_, channels_, options_, &out);
  hierarchy.Write();
  out += "MOTION\nFrames: ";
  out += std::to_string(frames);
  out += "\nFrame Time: ";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, 1.0 / frame_rate);
  out.append(buffer, result.ptr);
  out += '\n';
  return out;
}

Status BvhPieceWriter::AppendFrames(const Motion& piece, int first, int count, std::string* out) {
  if (frames_written_ > 0 || !first_piece_checked_) {
    Status status = CheckBvhWritable(*skeleton_, piece, options_);
    if (!status.ok()) return status;
    for (int j = 0; j < skeleton_->num_joints(); ++j) {  // Its channels among Start's.
      for (Channel c : OutputChannels(*skeleton_, MotionSamples(piece), j, options_.euler_order)) {
        if (std::find(channels_[j].begin(), channels_[j].end(), c) == channels_[j].end()) {
          return Status::Error("cannot write BVH: joint " + skeleton_->name(j) +
                               " moves on an axis with no channel in the first piece's frames");
        }
      }
    }
  }
  size_t num_columns = 0;
  for (const auto& list : channels_) num_columns += list.size();
  out->reserve(out->size() + static_cast<size_t>(count) * num_columns * (options_.precision + 3));
  for (int f = first; f < first + count; ++f) {
    const Pose& pose = piece.frames[f];
    bool first_value = true;
    for (int j : joint_order_) {
      // Fold the rest rotation in: BVH has none (see the header).
      const Eigen::Quaterniond rotation = skeleton_->has_rest_rotation(j)
                                              ? skeleton_->rest_rotation(j) * pose.rotations[j]
                                              : pose.rotations[j];
      Eigen::Vector3d angles = EulerFromQuaternion(rotation, orders_[j]);
      if (frames_written_ > 0) angles = NearestEquivalentEuler(angles, previous_angles_[j]);
      previous_angles_[j] = angles;
      int slot = 0;
      for (Channel c : channels_[j]) {
        double value;
        if (IsPosition(c)) {
          value = pose.translations[j][ChannelAxis(c)] * options_.scale;
        } else {
          value = RadToDeg(angles[slot++]);
          // Rounding noise of the Euler extraction (1e-14 degrees), not motion.
          if (std::abs(value) < kNoiseDegrees) value = 0.0;
        }
        if (!first_value) *out += ' ';
        first_value = false;
        AppendNumber(value, options_.precision, out);
      }
    }
    *out += '\n';
    ++frames_written_;
  }
  return Status::Ok();
}

std::string FormatBvh(const Skeleton& skeleton, const Motion& motion,
                      const BvhWriteOptions& options) {
  BvhPieceWriter writer;
  if (!writer.Start(skeleton, motion, options).ok()) return "";
  std::string out = writer.Header(motion.num_frames(), motion.frame_rate);
  if (!writer.AppendFrames(motion, 0, motion.num_frames(), &out).ok()) return "";
  return out;
}

Status WriteBvh(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                const BvhWriteOptions& options) {
  if (Status s = CheckBvhWritable(skeleton, motion, options); !s.ok()) {
    return Status::Error(path + ": " + s.message());
  }
  return WriteFileAtomically(path, FormatBvh(skeleton, motion, options));
}

Status WriteBvh(const std::string& path, const Skeleton& skeleton, const CompactMotion& motion,
                const BvhWriteOptions& options) {
  constexpr int kPieceFrames = 1024;  // ~4 MB of Xbot's Motion and ~1 MB of its text at a time.
  BvhPieceWriter writer;
  Status status = writer.Start(skeleton, motion, options);
  AtomicFileWriter file;
  if (status.ok()) status = file.Open(path);
  std::string text = status.ok() ? writer.Header(motion.num_frames(), motion.frame_rate()) : "";
  Motion piece;
  piece.frame_rate = motion.frame_rate();
  for (int first = 0; status.ok() && first < motion.num_frames(); first += kPieceFrames) {
    piece.frames.resize(std::min(kPieceFrames, motion.num_frames() - first));
    for (size_t f = 0; f < piece.frames.size(); ++f) motion.Frame(first + static_cast<int>(f), &piece.frames[f]);
    status = writer.AppendFrames(piece, 0, piece.num_frames(), &text);
    if (status.ok()) status = file.Append(text);
    text.clear();
  }
  if (status.ok()) status = file.Close();
  // The file's errors name it already; the writer's do not.
  return status.ok() || status.message().rfind(path, 0) == 0 ? status : Status::Error(path + ": " + status.message());
}

}  // namespace mocapsolve
