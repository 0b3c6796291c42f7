#include "io/asf_reader.h"

#include <charconv>
#include <cmath>
#include <map>
#include <string_view>
#include <system_error>
#include <utility>

#include "io/atomic_file.h"
#include "kinematics/quote_token.h"
#include "kinematics/rotation.h"

namespace mocapsolve {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::vector<std::string_view> SplitLines(const std::string& text) {
  std::vector<std::string_view> lines;
  size_t begin = 0;
  while (begin <= text.size()) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    lines.emplace_back(text.data() + begin, end - begin);
    begin = end + 1;
  }
  // A final newline does not start another line.
  if (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

// Whitespace-separated tokens; with split_parens, '(' and ')' are tokens of their own.
std::vector<std::string_view> Tokenize(std::string_view line, bool split_parens = false) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    if (IsBlank(line[i])) {
      ++i;
      continue;
    }
    if (split_parens && (line[i] == '(' || line[i] == ')')) {
      tokens.push_back(line.substr(i, 1));
      ++i;
      continue;
    }
    const size_t begin = i;
    while (i < line.size() && !IsBlank(line[i]) &&
           !(split_parens && (line[i] == '(' || line[i] == ')'))) {
      ++i;
    }
    tokens.push_back(line.substr(begin, i - begin));
  }
  return tokens;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

std::string Upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return out;
}

// The whole token must be a number ("inf" and "nan" included; callers check).
bool ParseNumber(std::string_view s, double* value) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), *value);
  return error == std::errc() && end == s.data() + s.size();
}

bool ParseFinite(std::string_view s, double* value) {
  return ParseNumber(s, value) && std::isfinite(*value);
}

bool ParseInt(std::string_view s, int* value) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  if (s.empty()) return false;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), *value);
  return error == std::errc() && end == s.data() + s.size();
}

// "rx" / "TX" ... (case-insensitive); "l" and anything else is false.
bool ParseDof(std::string_view token, AcclaimDof* dof) {
  const std::string t = Lower(token);
  static const std::pair<const char*, AcclaimDof> kDofs[] = {
      {"tx", AcclaimDof::kTx}, {"ty", AcclaimDof::kTy}, {"tz", AcclaimDof::kTz},
      {"rx", AcclaimDof::kRx}, {"ry", AcclaimDof::kRy}, {"rz", AcclaimDof::kRz}};
  for (const auto& [name, value] : kDofs) {
    if (t == name) {
      *dof = value;
      return true;
    }
  }
  return false;
}

// Acclaim applies the first-listed angle first: M = R_last ... R_first.
std::vector<int> RotationAxesInProductOrder(const std::vector<AsfDof>& dofs) {
  std::vector<int> axes;
  for (auto it = dofs.rbegin(); it != dofs.rend(); ++it) {
    if (IsRotationDof(it->dof)) axes.push_back(AcclaimDofAxis(it->dof));
  }
  return axes;
}

// The limits of those axes, in the same (product) order, radians; empty when none is
// finite.
std::vector<std::pair<double, double>> RotationLimitsInProductOrder(const std::vector<AsfDof>& dofs) {
  std::vector<std::pair<double, double>> limits;
  bool any = false;
  for (auto it = dofs.rbegin(); it != dofs.rend(); ++it) {
    if (!IsRotationDof(it->dof)) continue;
    limits.emplace_back(DegToRad(it->lower_deg), DegToRad(it->upper_deg));
    any |= std::isfinite(it->lower_deg) || std::isfinite(it->upper_deg);
  }
  if (!any) limits.clear();
  return limits;
}

Channel ChannelOf(AcclaimDof dof) {
  switch (dof) {
    case AcclaimDof::kTx: return Channel::kXposition;
    case AcclaimDof::kTy: return Channel::kYposition;
    case AcclaimDof::kTz: return Channel::kZposition;
    case AcclaimDof::kRx: return Channel::kXrotation;
    case AcclaimDof::kRy: return Channel::kYrotation;
    case AcclaimDof::kRz: return Channel::kZrotation;
  }
  return Channel::kXrotation;
}

bool ValidAxisOrder(std::string_view token) {
  EulerOrder unused;
  return ParseEulerOrder(std::string(token), &unused);
}

// A bone as read, angles still in the file's unit.
struct RawBone {
  AsfBone bone;
  int line = 0;  // 0-based index of 'begin'.
  bool has_name = false, has_direction = false, has_length = false, has_axis = false;
  bool has_dof = false, has_limits = false;
  std::vector<std::pair<double, double>> limits;  // File angle unit.
};

struct HierarchyLine {
  int line = 0;  // 0-based.
  std::vector<std::string> names;
};

class AsfParser {
 public:
  AsfParser(const std::string& text, const std::string& name)
      : name_(name), lines_(SplitLines(text)) {}

  Status Parse(Skeleton* skeleton, AsfInfo* info);

 private:
  // `line` is 0-based; messages use 1-based numbers.
  Status Error(size_t line, const std::string& message) const {
    return Status::Error(name_ + ":" + std::to_string(line + 1) + ": " + message);
  }
  // Line number to blame for "unexpected end of file".
  size_t LastLine() const { return lines_.empty() ? 0 : lines_.size() - 1; }

  // Moves next_ to the next line with content (not blank, not a '#' comment) and returns
  // its tokens, or returns false at the end of the text.
  bool NextContent(std::vector<std::string_view>* tokens, bool split_parens = false);
  // As NextContent, but stops (without consuming) at a ':' section line.
  bool NextBodyLine(std::vector<std::string_view>* tokens);
  void SkipSection();

  Status ParseUnits();
  Status ParseRoot(size_t section_line);
  Status ParseBonedata();
  Status ParseBone(size_t begin_line);
  Status ParseLimitPairs(size_t line, const std::vector<std::string_view>& tokens,
                         size_t first, RawBone* raw);
  Status ParseHierarchy();
  Status Build(Skeleton* skeleton, AsfInfo* info);

  std::string name_;
  std::vector<std::string_view> lines_;
  size_t next_ = 0;    // Index of the next unread line.
  size_t current_ = 0;  // Index of the line NextContent returned last.

  std::string version_, skeleton_name_;
  double mass_ = 1.0, length_ = 1.0;
  bool degrees_ = true;
  bool has_order_ = false;
  std::vector<AsfDof> root_order_;
  std::string root_axis_ = "XYZ";
  Eigen::Vector3d root_position_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d root_orientation_ = Eigen::Vector3d::Zero();
  std::vector<RawBone> bones_;
  std::map<std::string, int> bone_index_;
  std::vector<HierarchyLine> hierarchy_;
  std::map<std::string, size_t> sections_;  // Keyword -> line, to refuse repeats.
};

bool AsfParser::NextContent(std::vector<std::string_view>* tokens, bool split_parens) {
  while (next_ < lines_.size()) {
    const size_t i = next_++;
    std::vector<std::string_view> t = Tokenize(lines_[i], split_parens);
    if (t.empty() || t[0][0] == '#') continue;
    current_ = i;
    *tokens = std::move(t);
    return true;
  }
  current_ = LastLine();
  return false;
}

bool AsfParser::NextBodyLine(std::vector<std::string_view>* tokens) {
  const size_t saved = next_;
  if (!NextContent(tokens)) return false;
  if ((*tokens)[0][0] == ':') {
    next_ = saved;
    return false;
  }
  return true;
}

void AsfParser::SkipSection() {
  std::vector<std::string_view> tokens;
  while (NextBodyLine(&tokens)) {
  }
}

Status AsfParser::Parse(Skeleton* skeleton, AsfInfo* info) {
  std::vector<std::string_view> tokens;
  while (NextContent(&tokens)) {
    const size_t line = current_;
    if (tokens[0][0] != ':') {
      return Error(line, "expected a ':' keyword (':units', ':root', ':bonedata', ...), got " +
                             QuoteToken(tokens[0]));
    }
    const std::string keyword = Lower(tokens[0]);
    const auto [it, inserted] = sections_.emplace(keyword, line);
    if (!inserted) {
      return Error(line, "repeated " + keyword + " (first at line " +
                             std::to_string(it->second + 1) + ")");
    }
    Status status = Status::Ok();
    if (keyword == ":version") {
      if (tokens.size() > 1) version_ = std::string(tokens[1]);
    } else if (keyword == ":name") {
      for (size_t k = 1; k < tokens.size(); ++k) {
        skeleton_name_ += (k > 1 ? " " : "") + std::string(tokens[k]);
      }
    } else if (keyword == ":units") {
      status = ParseUnits();
    } else if (keyword == ":root") {
      status = ParseRoot(line);
    } else if (keyword == ":bonedata") {
      status = ParseBonedata();
    } else if (keyword == ":hierarchy") {
      status = ParseHierarchy();
    } else {
      SkipSection();  // :documentation, :skin and anything else: free text.
    }
    if (!status.ok()) return status;
  }
  return Build(skeleton, info);
}

Status AsfParser::ParseUnits() {
  std::vector<std::string_view> tokens;
  while (NextBodyLine(&tokens)) {
    const std::string key = Lower(tokens[0]);
    if (key != "mass" && key != "length" && key != "angle") continue;  // Other units: unused.
    if (tokens.size() != 2) return Error(current_, "expected '" + key + " <value>'");
    if (key == "angle") {
      const std::string unit = Lower(tokens[1]);
      if (unit == "deg" || unit == "degree" || unit == "degrees") {
        degrees_ = true;
      } else if (unit == "rad" || unit == "radian" || unit == "radians") {
        degrees_ = false;
      } else {
        return Error(current_, "angle unit must be 'deg' or 'rad', got " + QuoteToken(tokens[1]));
      }
      continue;
    }
    double value;
    if (!ParseFinite(tokens[1], &value) || !(value > 0.0)) {
      return Error(current_, key + " must be a positive number, got " + QuoteToken(tokens[1]));
    }
    (key == "mass" ? mass_ : length_) = value;
  }
  return Status::Ok();
}

Status AsfParser::ParseRoot(size_t section_line) {
  std::vector<std::string_view> tokens;
  bool has_axis = false, has_position = false, has_orientation = false;
  while (NextBodyLine(&tokens)) {
    const size_t line = current_;
    const std::string key = Lower(tokens[0]);
    if (key == "order") {
      if (has_order_) return Error(line, "repeated 'order'");
      has_order_ = true;
      for (size_t k = 1; k < tokens.size(); ++k) {
        AsfDof dof;
        if (!ParseDof(tokens[k], &dof.dof)) {
          return Error(line, "root order entries are TX TY TZ RX RY RZ, got " + QuoteToken(tokens[k]));
        }
        for (const AsfDof& seen : root_order_) {
          if (seen.dof == dof.dof) return Error(line, "repeated root order entry " + QuoteToken(tokens[k]));
        }
        root_order_.push_back(dof);
      }
    } else if (key == "axis") {
      if (has_axis) return Error(line, "repeated 'axis'");
      has_axis = true;
      if (tokens.size() != 2 || !ValidAxisOrder(tokens[1])) {
        return Error(line, "expected 'axis' and an order such as XYZ");
      }
      root_axis_ = Upper(tokens[1]);
    } else if (key == "position" || key == "orientation") {
      bool& seen = key == "position" ? has_position : has_orientation;
      if (seen) return Error(line, "repeated " + QuoteToken(key));
      seen = true;
      Eigen::Vector3d& v = key == "position" ? root_position_ : root_orientation_;
      if (tokens.size() != 4) return Error(line, "expected '" + key + " x y z'");
      for (int k = 0; k < 3; ++k) {
        if (!ParseFinite(tokens[k + 1], &v[k])) {
          return Error(line, "bad number " + QuoteToken(tokens[k + 1]) + " in " + QuoteToken(key));
        }
      }
    } else {
      return Error(line, "unknown :root entry " + QuoteToken(tokens[0]) +
                             " (expected order, axis, position, orientation)");
    }
  }
  if (!has_order_) return Error(section_line, ":root has no 'order' line");
  return Status::Ok();
}

Status AsfParser::ParseBonedata() {
  std::vector<std::string_view> tokens;
  while (NextBodyLine(&tokens)) {
    if (Lower(tokens[0]) != "begin" || tokens.size() != 1) {
      return Error(current_, "expected 'begin' of a bone, got " + QuoteToken(tokens[0]));
    }
    Status status = ParseBone(current_);
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Status AsfParser::ParseLimitPairs(size_t line, const std::vector<std::string_view>& tokens,
                                  size_t first, RawBone* raw) {
  size_t k = first;
  while (k < tokens.size()) {
    if (raw->limits.size() >= raw->bone.dofs.size()) {
      return Error(line, "more limits than dofs (" + std::to_string(raw->bone.dofs.size()) + ")");
    }
    double lo, hi;
    if (k + 3 >= tokens.size() || tokens[k] != "(" || tokens[k + 3] != ")" ||
        !ParseNumber(tokens[k + 1], &lo) || !ParseNumber(tokens[k + 2], &hi)) {
      return Error(line, "expected limits as '(lower upper)' at " + QuoteToken(tokens[k]));
    }
    if (std::isnan(lo) || std::isnan(hi) || lo > hi) {
      return Error(line, "bad limits (" + std::string(tokens[k + 1]) + " " +
                             std::string(tokens[k + 2]) + "): need lower <= upper");
    }
    raw->limits.emplace_back(lo, hi);
    k += 4;
  }
  return Status::Ok();
}

Status AsfParser::ParseBone(size_t begin_line) {
  RawBone raw;
  raw.line = static_cast<int>(begin_line);
  const std::string begun = " (bone begun at line " + std::to_string(begin_line + 1) + ")";
  std::vector<std::string_view> tokens;
  while (true) {
    if (!NextContent(&tokens)) {
      return Error(LastLine(), "end of file before 'end'" + begun);
    }
    const size_t line = current_;
    if (tokens[0][0] == ':') return Error(line, QuoteToken(tokens[0]) + " before 'end'" + begun);
    const std::string key = Lower(tokens[0]);
    if (key == "end") {
      if (tokens.size() != 1) return Error(line, "unexpected text after 'end'");
      break;
    }
    if (key == "begin") return Error(line, "'begin' before 'end'" + begun);
    if (key[0] == '(') return Error(line, "more limits than dofs, or limits outside 'limits'");
    if (key == "id") {
      if (tokens.size() != 2 || !ParseInt(tokens[1], &raw.bone.id)) {
        return Error(line, "expected 'id <integer>'");
      }
    } else if (key == "name") {
      if (raw.has_name) return Error(line, "repeated 'name'");
      if (tokens.size() != 2) return Error(line, "expected 'name <one word>'");
      raw.has_name = true;
      raw.bone.name = std::string(tokens[1]);
      if (raw.bone.name == "root") return Error(line, "a bone cannot be named 'root'");
      const auto found = bone_index_.find(raw.bone.name);
      if (found != bone_index_.end()) {
        return Error(line, "bone name " + QuoteToken(tokens[1]) + " already used at line " +
                               std::to_string(bones_[found->second].line + 1));
      }
    } else if (key == "direction") {
      if (raw.has_direction) return Error(line, "repeated 'direction'");
      raw.has_direction = true;
      if (tokens.size() != 4) return Error(line, "expected 'direction x y z'");
      for (int k = 0; k < 3; ++k) {
        if (!ParseFinite(tokens[k + 1], &raw.bone.direction[k])) {
          return Error(line, "bad number " + QuoteToken(tokens[k + 1]) + " in 'direction'");
        }
      }
    } else if (key == "length") {
      if (raw.has_length) return Error(line, "repeated 'length'");
      raw.has_length = true;
      if (tokens.size() != 2 || !ParseFinite(tokens[1], &raw.bone.length) ||
          raw.bone.length < 0.0) {
        return Error(line, "expected 'length <non-negative number>'");
      }
    } else if (key == "axis") {
      if (raw.has_axis) return Error(line, "repeated 'axis'");
      raw.has_axis = true;
      if (tokens.size() != 5 || !ValidAxisOrder(tokens[4])) {
        return Error(line, "expected 'axis x y z ORDER' (ORDER such as XYZ)");
      }
      for (int k = 0; k < 3; ++k) {
        if (!ParseFinite(tokens[k + 1], &raw.bone.axis_deg[k])) {
          return Error(line, "bad number " + QuoteToken(tokens[k + 1]) + " in 'axis'");
        }
      }
      raw.bone.axis_order = Upper(tokens[4]);
    } else if (key == "dof") {
      if (raw.has_dof) return Error(line, "repeated 'dof'");
      raw.has_dof = true;
      for (size_t k = 1; k < tokens.size(); ++k) {
        AsfDof dof;
        if (!ParseDof(tokens[k], &dof.dof) || !IsRotationDof(dof.dof)) {
          return Error(line, "unsupported dof " + QuoteToken(tokens[k]) + " (only rx ry rz)");
        }
        for (const AsfDof& seen : raw.bone.dofs) {
          if (seen.dof == dof.dof) return Error(line, "repeated dof " + QuoteToken(tokens[k]));
        }
        raw.bone.dofs.push_back(dof);
      }
    } else if (key == "limits") {
      if (raw.has_limits) return Error(line, "repeated 'limits'");
      if (!raw.has_dof) return Error(line, "'limits' before 'dof'");
      raw.has_limits = true;
      Status status = ParseLimitPairs(line, Tokenize(lines_[line], true), 1, &raw);
      if (!status.ok()) return status;
      // The remaining pairs follow on lines that start with '('.
      while (raw.limits.size() < raw.bone.dofs.size()) {
        const size_t saved = next_;
        std::vector<std::string_view> more;
        if (!NextContent(&more, true) || more[0] != "(") {
          next_ = saved;
          break;
        }
        status = ParseLimitPairs(current_, more, 0, &raw);
        if (!status.ok()) return status;
      }
      if (raw.limits.size() != raw.bone.dofs.size()) {
        return Error(line, "expected " + std::to_string(raw.bone.dofs.size()) +
                               " limit pairs (one per dof), got " +
                               std::to_string(raw.limits.size()));
      }
    } else if (key == "bodymass" || key == "cofmass") {
      // Not used.
    } else {
      return Error(line, "unknown bone entry " + QuoteToken(tokens[0]));
    }
  }
  const char* missing = !raw.has_name        ? "name"
                        : !raw.has_direction ? "direction"
                        : !raw.has_length    ? "length"
                        : !raw.has_axis      ? "axis"
                                             : nullptr;
  if (missing != nullptr) {
    return Error(begin_line, "bone " + (raw.has_name ? QuoteToken(raw.bone.name) + " " : "") +
                                 "has no " + QuoteToken(missing));
  }
  const double norm = raw.bone.direction.norm();
  if (norm == 0.0 && raw.bone.length > 0.0) {
    return Error(begin_line, "bone " + QuoteToken(raw.bone.name) + " has a zero direction");
  }
  if (norm > 0.0) raw.bone.direction /= norm;
  raw.bone.line = static_cast<int>(begin_line + 1);
  bone_index_.emplace(raw.bone.name, static_cast<int>(bones_.size()));
  bones_.push_back(std::move(raw));
  return Status::Ok();
}

Status AsfParser::ParseHierarchy() {
  std::vector<std::string_view> tokens;
  if (!NextBodyLine(&tokens) || Lower(tokens[0]) != "begin" || tokens.size() != 1) {
    return Error(current_, "expected 'begin' after :hierarchy");
  }
  const size_t begin_line = current_;
  while (true) {
    if (!NextBodyLine(&tokens)) {
      return Error(current_, "missing 'end' of :hierarchy (begun at line " +
                                 std::to_string(begin_line + 1) + ")");
    }
    if (Lower(tokens[0]) == "end" && tokens.size() == 1) break;
    HierarchyLine entry;
    entry.line = static_cast<int>(current_);
    for (std::string_view t : tokens) entry.names.emplace_back(t);
    hierarchy_.push_back(std::move(entry));
  }
  if (NextBodyLine(&tokens)) {
    return Error(current_, "unexpected " + QuoteToken(tokens[0]) + " after the :hierarchy 'end'");
  }
  return Status::Ok();
}

Status AsfParser::Build(Skeleton* skeleton, AsfInfo* info) {
  if (sections_.count(":root") == 0) return Error(LastLine(), "no :root section");
  if (sections_.count(":bonedata") == 0) return Error(LastLine(), "no :bonedata section");
  const int num_bones = static_cast<int>(bones_.size());
  if (num_bones > 0 && sections_.count(":hierarchy") == 0) {
    return Error(LastLine(), "no :hierarchy section");
  }
  const double to_deg = degrees_ ? 1.0 : 180.0 / kPi;

  // Tree: node 0 is the root, node b + 1 is bone b.
  std::vector<int> parent(num_bones + 1, -2);
  std::vector<int> parent_line(num_bones + 1, 0);
  std::vector<std::vector<int>> children(num_bones + 1);
  auto node_of = [&](const std::string& name) {
    if (name == "root") return 0;
    const auto it = bone_index_.find(name);
    return it == bone_index_.end() ? -1 : it->second + 1;
  };
  for (const HierarchyLine& entry : hierarchy_) {
    const int p = node_of(entry.names[0]);
    if (p < 0) return Error(entry.line, "unknown bone " + QuoteToken(entry.names[0]));
    for (size_t k = 1; k < entry.names.size(); ++k) {
      const int c = node_of(entry.names[k]);
      if (c < 0) return Error(entry.line, "unknown bone " + QuoteToken(entry.names[k]));
      if (c == 0) return Error(entry.line, "'root' cannot be a child");
      if (c == p) return Error(entry.line, "bone " + QuoteToken(entry.names[k]) + " is its own parent");
      if (parent[c] != -2) {
        return Error(entry.line, "bone " + QuoteToken(entry.names[k]) + " already has a parent (line " +
                                     std::to_string(parent_line[c] + 1) + ")");
      }
      parent[c] = p;
      parent_line[c] = entry.line;
      children[p].push_back(c);
    }
  }
  for (int b = 0; b < num_bones; ++b) {
    if (parent[b + 1] == -2) {
      return Error(bones_[b].line, "bone " + QuoteToken(bones_[b].bone.name) +
                                       " is not a child of anything in :hierarchy");
    }
  }
  // Preorder, children in the listed order; an explicit stack (no recursion depth limit).
  std::vector<int> order;
  order.reserve(num_bones + 1);
  std::vector<bool> visited(num_bones + 1, false);
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    visited[node] = true;
    order.push_back(node);
    for (auto it = children[node].rbegin(); it != children[node].rend(); ++it) stack.push_back(*it);
  }
  for (int b = 0; b < num_bones; ++b) {
    if (!visited[b + 1]) {
      return Error(bones_[b].line, "bone " + QuoteToken(bones_[b].bone.name) +
                                       " is not connected to the root (cycle in :hierarchy)");
    }
  }

  AsfInfo out;
  out.version = version_;
  out.name = skeleton_name_;
  out.mass_scale = mass_;
  out.length_scale = length_;
  out.angles_in_degrees = degrees_;
  out.root_order = root_order_;
  out.root_axis_order = root_axis_;
  out.root_position = root_position_;
  out.root_orientation_deg = root_orientation_ * to_deg;
  out.root_axis_rotation =
      AcclaimAxisRotation(out.root_orientation_deg * (kPi / 180.0), out.root_axis_order);
  for (RawBone& raw : bones_) {
    AsfBone bone = std::move(raw.bone);
    bone.axis_deg *= to_deg;
    bone.axis_rotation = AcclaimAxisRotation(bone.axis_deg * (kPi / 180.0), bone.axis_order);
    for (size_t k = 0; k < raw.limits.size(); ++k) {
      bone.dofs[k].lower_deg = raw.limits[k].first * to_deg;
      bone.dofs[k].upper_deg = raw.limits[k].second * to_deg;
    }
    out.bones.push_back(std::move(bone));
  }

  std::vector<int> joint_of_node(num_bones + 1, -1);
  std::vector<JointSpec> joints;
  std::vector<EndSite> end_sites;
  out.bone_of_joint.assign(num_bones + 1, -1);
  for (int node : order) {
    const int j = static_cast<int>(joints.size());
    joint_of_node[node] = j;
    JointSpec spec;
    if (node == 0) {
      spec.name = "root";
      spec.parent = -1;
      spec.offset = out.root_position;
      spec.rest_rotation = out.root_axis_rotation;
      for (const AsfDof& dof : out.root_order) spec.channels.push_back(ChannelOf(dof.dof));
      spec.rotation_axes = RotationAxesInProductOrder(out.root_order);
    } else {
      const int b = node - 1;
      AsfBone& bone = out.bones[b];
      const int p = parent[node];
      bone.joint = j;
      bone.parent_joint = joint_of_node[p];
      out.bone_of_joint[j] = b;
      const Eigen::Quaterniond parent_axis =
          p == 0 ? out.root_axis_rotation : out.bones[p - 1].axis_rotation;
      spec.name = bone.name;
      spec.parent = bone.parent_joint;
      if (p != 0) {
        const AsfBone& parent_bone = out.bones[p - 1];
        spec.offset = parent_axis.conjugate() * (parent_bone.direction * parent_bone.length);
      }
      spec.rest_rotation = (parent_axis.conjugate() * bone.axis_rotation).normalized();
      for (const AsfDof& dof : bone.dofs) spec.channels.push_back(ChannelOf(dof.dof));
      spec.rotation_axes = RotationAxesInProductOrder(bone.dofs);
      spec.rotation_limits = RotationLimitsInProductOrder(bone.dofs);
      if (children[node].empty()) {
        EndSite site;
        site.name = bone.name + "_End";
        site.parent = j;
        site.offset = bone.axis_rotation.conjugate() * (bone.direction * bone.length);
        end_sites.push_back(std::move(site));
      }
    }
    joints.push_back(std::move(spec));
  }
  Status status = Skeleton::Create(std::move(joints), std::move(end_sites),
                                   AcclaimLength(length_), skeleton);
  if (!status.ok()) return Status::Error(name_ + ": " + status.message());
  *info = std::move(out);
  return Status::Ok();
}

}  // namespace

std::string AcclaimDofName(AcclaimDof dof) {
  static const char* const kNames[] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  return kNames[static_cast<int>(dof)];
}

int AsfInfo::FindBone(const std::string& name) const {
  for (size_t b = 0; b < bones.size(); ++b) {
    if (bones[b].name == name) return static_cast<int>(b);
  }
  return -1;
}

Eigen::Quaterniond AcclaimEulerRotation(int count, const int* axes, const double* angles_rad) {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int i = 0; i < count; ++i) {
    q = Eigen::Quaterniond(Eigen::AngleAxisd(angles_rad[i], Eigen::Vector3d::Unit(axes[i]))) * q;
  }
  return q.normalized();
}

Eigen::Quaterniond AcclaimAxisRotation(const Eigen::Vector3d& xyz_angles_rad,
                                       const std::string& order) {
  int axes[3] = {0, 1, 2};
  double angles[3];
  for (int i = 0; i < 3; ++i) {
    const char c = i < static_cast<int>(order.size()) ? order[i] : static_cast<char>('X' + i);
    axes[i] = (c == 'x' || c == 'X') ? 0 : (c == 'y' || c == 'Y') ? 1 : 2;
    angles[i] = xyz_angles_rad[axes[i]];
  }
  return AcclaimEulerRotation(3, axes, angles);
}

Status ParseAsf(const std::string& text, const std::string& name_for_errors, Skeleton* skeleton,
                AsfInfo* info) {
  AsfParser parser(text, name_for_errors);
  return parser.Parse(skeleton, info);
}

Status ReadAsf(const std::string& path, Skeleton* skeleton, AsfInfo* info) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  return ParseAsf(text, path, skeleton, info);
}

}  // namespace mocapsolve
