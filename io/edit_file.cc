#include "io/edit_file.h"

#include <cmath>
#include <set>

#include "io/atomic_file.h"
#include "io/input_limits.h"
#include "io/json_reader.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

constexpr const char* kFormat = "mocapsolve.edit";
constexpr double kPiOver180 = 3.14159265358979323846 / 180.0;

class Interpreter {
 public:
  Interpreter(const std::string& file_name, const Skeleton& skeleton)
      : file_name_(file_name), skeleton_(skeleton) {}

  Status Error(const JsonNode& node, const std::string& field, const std::string& message) const {
    return Status::Error(node.Where(file_name_) + ": " + field + ": " + message);
  }

  Status CheckKeys(const JsonNode& object, const std::set<std::string>& allowed,
                   const std::string& prefix) const {
    if (const auto* member = FindUnknownKey(object, allowed)) {
      return Error(member->second, prefix + member->first, "unknown key (known: " + KeyList(allowed) + ")");
    }
    return Status::Ok();
  }

  Status Vector3(const JsonNode& node, const std::string& field, Eigen::Vector3d* v) const {
    if (!node.is_array()) {
      return Error(node, field, std::string("expected an array of 3 numbers, got ") + JsonTypeName(node.type));
    }
    if (node.items.size() != 3) {
      return Error(node, field, "expected 3 numbers, got " + std::to_string(node.items.size()));
    }
    for (int i = 0; i < 3; ++i) {
      if (!node.items[i].is_number()) {
        return Error(node.items[i], field + "[" + std::to_string(i) + "]",
                     std::string("expected a number, got ") + JsonTypeName(node.items[i].type));
      }
      // Offsets and angles beyond io/input_limits.h's coordinates would only make a
      // motion no writer can hold (the BVH writer refused it, naming the output).
      if (!(std::abs(node.items[i].number) <= kMaxCoordinate)) {
        return Error(node.items[i], field + "[" + std::to_string(i) + "]",
                     ShortNumber(node.items[i].number) + " is beyond +-" + ShortNumber(kMaxCoordinate));
      }
      (*v)[i] = node.items[i].number;
    }
    return Status::Ok();
  }

  // One edit object; prefix names it in messages ("" or "edits[2].").
  Status Edit(const JsonNode& node, const std::string& prefix, const std::set<std::string>& extra_keys,
              EditFileEntry* edit) const {
    std::set<std::string> keys = {"frame", "joints", "root_translation_offset"};
    keys.insert(extra_keys.begin(), extra_keys.end());
    Status status = CheckKeys(node, keys, prefix);
    if (!status.ok()) return status;
    const JsonNode* frame = node.Find("frame");
    if (frame == nullptr) return Error(node, prefix + "frame", "missing (the edited frame, 0-based)");
    if (!frame->is_number() || frame->number != std::floor(frame->number) || frame->number < 0 ||
        frame->number > 1e9) {
      return Error(*frame, prefix + "frame", "expected a frame index (integer >= 0)");
    }
    edit->frame = static_cast<int>(frame->number);
    edit->where = frame->Where(file_name_);
    bool changes = false;
    if (const JsonNode* joints = node.Find("joints")) {
      if (!joints->is_object()) {
        return Error(*joints, prefix + "joints", std::string("expected an object, got ") + JsonTypeName(joints->type));
      }
      for (const auto& [name, value] : joints->members) {
        const std::string field = prefix + "joints." + name;
        const int joint = skeleton_.FindJoint(name);
        if (joint < 0) return Error(value, prefix + "joints", "unknown joint " + QuoteToken(name));
        if (!value.is_object()) {
          return Error(value, field, std::string("expected an object, got ") + JsonTypeName(value.type));
        }
        status = CheckKeys(value, {"rotation_offset_deg"}, field + ".");
        if (!status.ok()) return status;
        const JsonNode* offset = value.Find("rotation_offset_deg");
        if (offset == nullptr) return Error(value, field + ".rotation_offset_deg", "missing");
        Eigen::Vector3d degrees;
        status = Vector3(*offset, field + ".rotation_offset_deg", &degrees);
        if (!status.ok()) return status;
        if (skeleton_.num_rotation_dofs(joint) == 0) {
          return Error(value, field, "joint " + QuoteToken(name) + " has no rotation channels");
        }
        edit->rotation_offsets_rad.emplace_back(joint, degrees * kPiOver180);
        changes = true;
      }
    }
    if (const JsonNode* root = node.Find("root_translation_offset")) {
      status = Vector3(*root, prefix + "root_translation_offset", &edit->root_translation_offset);
      if (!status.ok()) return status;
      changes = true;
    }
    if (!changes) {
      return Error(node, prefix.empty() ? std::string("edit") : prefix.substr(0, prefix.size() - 1),
                   "changes nothing (give \"joints\" or \"root_translation_offset\")");
    }
    return Status::Ok();
  }

  Status Run(const JsonNode& root, std::vector<EditFileEntry>* edits) const {
    if (!root.is_object()) {
      return Error(root, "top level", std::string("expected an object, got ") + JsonTypeName(root.type));
    }
    if (const JsonNode* format = root.Find("format")) {
      if (!format->is_string() || format->string != kFormat) {
        return Error(*format, "format", std::string("expected \"") + kFormat + "\"");
      }
    }
    if (const JsonNode* version = root.Find("version")) {
      if (!version->is_number() || version->number != 1.0) return Error(*version, "version", "expected 1");
    }
    if (const JsonNode* comment = root.Find("comment")) {
      if (!comment->is_string()) return Error(*comment, "comment", "expected a string");
    }
    const std::set<std::string> header = {"format", "version", "comment"};
    std::vector<EditFileEntry> result;
    if (const JsonNode* list = root.Find("edits")) {
      Status status = CheckKeys(root, {"format", "version", "comment", "edits"}, "");
      if (!status.ok()) return status;
      if (!list->is_array()) {
        return Error(*list, "edits", std::string("expected an array, got ") + JsonTypeName(list->type));
      }
      if (list->items.empty()) return Error(*list, "edits", "expected at least one edit");
      std::set<int> frames;
      for (size_t k = 0; k < list->items.size(); ++k) {
        const std::string prefix = "edits[" + std::to_string(k) + "].";
        const JsonNode& item = list->items[k];
        if (!item.is_object()) {
          return Error(item, prefix.substr(0, prefix.size() - 1),
                       std::string("expected an object, got ") + JsonTypeName(item.type));
        }
        EditFileEntry edit;
        status = Edit(item, prefix, {}, &edit);
        if (!status.ok()) return status;
        if (!frames.insert(edit.frame).second) {
          return Error(*item.Find("frame"), prefix + "frame",
                       "frame " + std::to_string(edit.frame) + " is edited twice");
        }
        result.push_back(std::move(edit));
      }
    } else {
      EditFileEntry edit;
      Status status = Edit(root, "", header, &edit);
      if (!status.ok()) return status;
      result.push_back(std::move(edit));
    }
    *edits = std::move(result);
    return Status::Ok();
  }

 private:
  std::string file_name_;
  const Skeleton& skeleton_;
};

}  // namespace

Status ParseEditFile(std::string_view text, const std::string& file_name, const Skeleton& skeleton,
                     std::vector<EditFileEntry>* edits) {
  JsonNode root;
  Status status = ParseJson(text, file_name, &root);
  if (!status.ok()) return status;
  return Interpreter(file_name, skeleton).Run(root, edits);
}

Status ReadEditFile(const std::string& path, const Skeleton& skeleton,
                    std::vector<EditFileEntry>* edits) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  return ParseEditFile(text, path, skeleton, edits);
}

}  // namespace mocapsolve
