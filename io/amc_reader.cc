#include "io/amc_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "io/atomic_file.h"
#include "kinematics/quote_token.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Splits `line` into whitespace-separated tokens (into *tokens, reused).
void Tokenize(std::string_view line, std::vector<std::string_view>* tokens) {
  tokens->clear();
  size_t i = 0;
  while (i < line.size()) {
    if (IsBlank(line[i])) {
      ++i;
      continue;
    }
    const size_t begin = i;
    while (i < line.size() && !IsBlank(line[i])) ++i;
    tokens->push_back(line.substr(begin, i - begin));
  }
}

std::string Upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

bool ParseFinite(std::string_view s, double* value) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), *value);
  return error == std::errc() && end == s.data() + s.size() && std::isfinite(*value);
}

// A frame-number line: one token of digits only.
bool ParseFrameNumber(const std::vector<std::string_view>& tokens, long long* number) {
  if (tokens.size() != 1) return false;
  const std::string_view t = tokens[0];
  for (char c : t) {
    if (c < '0' || c > '9') return false;
  }
  const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), *number);
  return error == std::errc() && end == t.data() + t.size();
}

// What one AMC line name stands for: the root (bone == -1) or a bone.
struct Slot {
  std::string name;
  int joint = 0;
  int bone = -1;
  const std::vector<AsfDof>* dofs = nullptr;
};

}  // namespace

Status ParseAmc(const std::string& text, const std::string& name_for_errors,
                const Skeleton& skeleton, const AsfInfo& info, double frame_rate,
                Motion* motion) {
  auto error = [&](size_t line, const std::string& message) {
    return Status::Error(name_for_errors + ":" + std::to_string(line + 1) + ": " + message);
  };
  if (!(frame_rate > 0.0) || !std::isfinite(frame_rate)) {
    return Status::Error(name_for_errors + ": frame rate must be positive, got " +
                         std::to_string(frame_rate));
  }
  // The skeleton and info must come from the same ASF.
  const int num_joints = skeleton.num_joints();
  if (static_cast<int>(info.bone_of_joint.size()) != num_joints ||
      static_cast<int>(info.bones.size()) + 1 != num_joints) {
    return Status::Error(name_for_errors + ": the ASF info does not match the skeleton");
  }
  std::vector<Slot> slots;
  slots.reserve(num_joints);
  slots.push_back({"root", 0, -1, &info.root_order});
  for (size_t b = 0; b < info.bones.size(); ++b) {
    const AsfBone& bone = info.bones[b];
    if (bone.joint <= 0 || bone.joint >= num_joints || skeleton.name(bone.joint) != bone.name) {
      return Status::Error(name_for_errors + ": the ASF info does not match the skeleton (bone '" +
                           bone.name + "')");
    }
    slots.push_back({bone.name, bone.joint, static_cast<int>(b), &bone.dofs});
  }
  std::unordered_map<std::string_view, int> slot_of_name;
  for (size_t s = 0; s < slots.size(); ++s) slot_of_name.emplace(slots[s].name, static_cast<int>(s));

  bool degrees = info.angles_in_degrees;
  const Pose rest = RestPose(skeleton);
  Motion out;
  out.frame_rate = frame_rate;

  std::vector<size_t> seen_line(slots.size());  // 1-based line of the slot in this frame, 0 = not yet.
  size_t frame_line = 0;                        // 0-based line of the current frame number.
  long long frame_number = 0;
  bool in_frame = false;
  Pose pose;
  // Checks the current frame is complete and appends it.
  auto finish_frame = [&]() -> Status {
    for (size_t s = 0; s < slots.size(); ++s) {
      if (seen_line[s] == 0 && !slots[s].dofs->empty()) {
        return error(frame_line, "frame " + std::to_string(frame_number) + " has no line for '" +
                                     slots[s].name + "'");
      }
    }
    out.frames.push_back(pose);
    return Status::Ok();
  };

  std::vector<std::string_view> tokens;
  std::vector<double> values;
  int axes[3];
  double angles[3];
  size_t begin = 0;
  size_t line = 0;
  for (; begin < text.size(); ++line) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    Tokenize(std::string_view(text.data() + begin, end - begin), &tokens);
    begin = end + 1;
    if (tokens.empty() || tokens[0][0] == '#') continue;

    if (tokens[0][0] == ':') {
      if (in_frame) return error(line, "keyword " + QuoteToken(tokens[0]) + " after the first frame");
      const std::string keyword = Upper(tokens[0]);
      if (keyword == ":DEGREES") degrees = true;
      if (keyword == ":RADIANS") degrees = false;
      continue;  // :FULLY-SPECIFIED and anything else: nothing to do.
    }

    long long number;
    if (ParseFrameNumber(tokens, &number)) {
      if (in_frame) {
        Status status = finish_frame();
        if (!status.ok()) return status;
        if (number - 1 != frame_number) {  // number >= 0: no overflow.
          return error(line, "frame " + std::to_string(number) + " follows frame " +
                                 std::to_string(frame_number) + " (frames must be consecutive)");
        }
      }
      in_frame = true;
      frame_number = number;
      frame_line = line;
      pose = rest;
      std::fill(seen_line.begin(), seen_line.end(), 0);
      continue;
    }

    if (!in_frame) {
      return error(line, "expected a frame number before bone data, got " + QuoteToken(tokens[0]));
    }
    const auto found = slot_of_name.find(tokens[0]);
    if (found == slot_of_name.end()) return error(line, "unknown bone " + QuoteToken(tokens[0]));
    const int s = found->second;
    const Slot& slot = slots[s];
    if (seen_line[s] != 0) {
      return error(line, "bone " + QuoteToken(slot.name) + " repeated in frame " +
                             std::to_string(frame_number) + " (first at line " +
                             std::to_string(seen_line[s]) + ")");
    }
    seen_line[s] = line + 1;
    const std::vector<AsfDof>& dofs = *slot.dofs;
    if (tokens.size() - 1 != dofs.size()) {
      return error(line, "bone " + QuoteToken(slot.name) + " has " + std::to_string(dofs.size()) +
                             " dofs, got " + std::to_string(tokens.size() - 1) + " values");
    }
    values.resize(dofs.size());
    for (size_t k = 0; k < dofs.size(); ++k) {
      if (!ParseFinite(tokens[k + 1], &values[k])) {
        return error(line, "bad number " + QuoteToken(tokens[k + 1]) + " for " + QuoteToken(slot.name) + " " +
                               AcclaimDofName(dofs[k].dof));
      }
    }
    int count = 0;
    for (size_t k = 0; k < dofs.size(); ++k) {
      if (IsRotationDof(dofs[k].dof)) {
        axes[count] = AcclaimDofAxis(dofs[k].dof);
        angles[count] = degrees ? DegToRad(values[k]) : values[k];
        ++count;
      } else {
        pose.translations[slot.joint][AcclaimDofAxis(dofs[k].dof)] += values[k];
      }
    }
    pose.rotations[slot.joint] = AcclaimEulerRotation(count, axes, angles);
  }
  if (!in_frame) return error(line == 0 ? 0 : line - 1, "no frames");
  Status status = finish_frame();
  if (!status.ok()) return status;
  MakeSignContinuous(&out);
  *motion = std::move(out);
  return Status::Ok();
}

Status ReadAmc(const std::string& path, const Skeleton& skeleton, const AsfInfo& info,
               double frame_rate, Motion* motion) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  return ParseAmc(text, path, skeleton, info, frame_rate, motion);
}

}  // namespace mocapsolve
