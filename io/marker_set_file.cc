#include "io/marker_set_file.h"

#include <cmath>
#include <cstdlib>
#include <set>
#include <vector>

#include "io/atomic_file.h"
#include "io/json_reader.h"
#include "io/json_writer.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

// Largest attachment weight (weights are renormalized per marker; this keeps their sum finite).
constexpr double kMaxWeight = 1e6;

constexpr const char* kFormat = "mocapsolve.markerset";

// The unit a marker set file names: the skeleton's own by name, a marker-file unit
// (mm, cm, m, in), or an ASF "asf length L ..." unit; unknown otherwise.
LengthUnit ResolveUnit(const std::string& name, const Skeleton& skeleton) {
  if (name == skeleton.unit().name) return skeleton.unit();
  LengthUnit unit = LengthUnitFromName(name);
  if (unit.known()) return unit;
  const std::string asf = "asf length ";
  if (name.compare(0, asf.size(), asf) == 0) {
    const char* begin = name.c_str() + asf.size();
    char* end = nullptr;
    const double length = std::strtod(begin, &end);
    if (end != begin && std::isfinite(length) && length > 0.0) return AcclaimLength(length);
  }
  return {name, 0.0};
}

class Interpreter {
 public:
  Interpreter(const std::string& file_name, const Skeleton& skeleton)
      : file_name_(file_name), skeleton_(skeleton) {}

  Status Error(const JsonNode& node, const std::string& message) const {
    return Status::Error(node.Where(file_name_) + ": " + context_ + message);
  }

  Status CheckType(const JsonNode& node, JsonNode::Type type, const std::string& field) const {
    if (node.type == type) return Status::Ok();
    return Error(node, field + ": expected " + JsonTypeName(type) + ", got " + JsonTypeName(node.type));
  }

  Status CheckKeys(const JsonNode& object, const std::set<std::string>& allowed,
                   const std::string& prefix) const {
    if (const auto* member = FindUnknownKey(object, allowed)) {
      return Error(member->second, prefix + "unknown key " + QuoteToken(member->first) + " (known: " + KeyList(allowed) + ")");
    }
    return Status::Ok();
  }

  Status Run(const JsonNode& root, MarkerSet* marker_set) {
    if (!root.is_object()) return Error(root, "expected a marker set object, got " + std::string(JsonTypeName(root.type)));
    Status status = CheckKeys(root, {"format", "version", "units", "skeleton", "markers"}, "");
    if (!status.ok()) return status;
    const JsonNode* format = root.Find("format");
    if (format == nullptr) return Error(root, "missing \"format\": \"" + std::string(kFormat) + "\"");
    if (!format->is_string() || format->string != kFormat) {
      return Error(*format, "format: expected \"" + std::string(kFormat) + "\"");
    }
    const JsonNode* version = root.Find("version");
    if (version == nullptr) return Error(root, "missing \"version\"");
    if (!version->is_number() || (version->number != 1.0 && version->number != 2.0)) {
      return Error(*version, "version: expected 1 or 2 (the versions this build reads)");
    }
    const JsonNode* units = root.Find("units");
    if (units == nullptr) return Error(root, "missing \"units\"");
    status = CheckType(*units, JsonNode::Type::kString, "units");
    if (!status.ok()) return status;
    status = UnitFactor(*units);
    if (!status.ok()) return status;
    if (const JsonNode* skeleton = root.Find("skeleton")) {
      status = CheckType(*skeleton, JsonNode::Type::kString, "skeleton");
      if (!status.ok()) return status;
    }
    const JsonNode* markers = root.Find("markers");
    if (markers == nullptr) return Error(root, "missing \"markers\"");
    status = CheckType(*markers, JsonNode::Type::kArray, "markers");
    if (!status.ok()) return status;

    std::vector<MarkerSpec> specs;
    std::set<std::string> labels;
    for (size_t m = 0; m < markers->items.size(); ++m) {
      context_ = "markers[" + std::to_string(m) + "]: ";
      MarkerSpec spec;
      status = ReadMarker(markers->items[m], &labels, &spec);
      if (!status.ok()) return status;
      specs.push_back(std::move(spec));
    }
    context_.clear();
    MarkerSet result;
    status = MarkerSet::Create(skeleton_, std::move(specs), &result);
    if (!status.ok()) return Error(*markers, status.message());  // Checked above; belt and braces.
    *marker_set = std::move(result);
    return Status::Ok();
  }

 private:
  Status UnitFactor(const JsonNode& units) {
    const LengthUnit& skeleton_unit = skeleton_.unit();
    if (units.string == skeleton_unit.name || !skeleton_unit.known()) return Status::Ok();
    const LengthUnit file_unit = ResolveUnit(units.string, skeleton_);
    if (!file_unit.known()) {
      return Error(units, "units: " + QuoteToken(units.string) + " is not a known length unit and not the skeleton's ('" +
                              skeleton_unit.name + "')");
    }
    factor_ = file_unit.metres_per_unit / skeleton_unit.metres_per_unit;
    return Status::Ok();
  }

  Status ReadMarker(const JsonNode& node, std::set<std::string>* labels, MarkerSpec* spec) {
    Status status = CheckType(node, JsonNode::Type::kObject, "marker");
    if (!status.ok()) return status;
    const JsonNode* label = node.Find("label");
    if (label == nullptr) return Error(node, "missing \"label\"");
    status = CheckType(*label, JsonNode::Type::kString, "label");
    if (!status.ok()) return status;
    if (label->string.empty()) return Error(*label, "label: empty");
    context_ += QuoteToken(label->string) + ": ";
    if (!labels->insert(label->string).second) return Error(*label, "label: duplicate");
    status = CheckKeys(node, {"label", "attachments", "solve_weight"}, "");
    if (!status.ok()) return status;
    spec->label = label->string;
    if (const JsonNode* solve_weight = node.Find("solve_weight")) {
      status = CheckType(*solve_weight, JsonNode::Type::kNumber, "solve_weight");
      if (!status.ok()) return status;
      if (!(solve_weight->number > 0.0 && solve_weight->number <= kMaxWeight)) {
        return Error(*solve_weight, "solve_weight: expected in (0, 1e6]");
      }
      spec->solve_weight = solve_weight->number;
    }
    const JsonNode* attachments = node.Find("attachments");
    if (attachments == nullptr) return Error(node, "missing \"attachments\"");
    status = CheckType(*attachments, JsonNode::Type::kArray, "attachments");
    if (!status.ok()) return status;
    if (attachments->items.empty()) return Error(*attachments, "attachments: empty (a marker needs a joint)");
    double total_weight = 0.0;
    for (size_t k = 0; k < attachments->items.size(); ++k) {
      const std::string field = "attachments[" + std::to_string(k) + "]";
      const JsonNode& a = attachments->items[k];
      status = CheckType(a, JsonNode::Type::kObject, field);
      if (!status.ok()) return status;
      status = CheckKeys(a, {"joint", "weight", "offset"}, field + ": ");
      if (!status.ok()) return status;
      MarkerAttachment attachment;
      const JsonNode* joint = a.Find("joint");
      if (joint == nullptr) return Error(a, field + ": missing \"joint\"");
      status = CheckType(*joint, JsonNode::Type::kString, field + ".joint");
      if (!status.ok()) return status;
      attachment.joint = skeleton_.FindJoint(joint->string);
      if (attachment.joint < 0) return Error(*joint, field + ".joint: unknown joint " + QuoteToken(joint->string));
      if (const JsonNode* weight = a.Find("weight")) {
        status = CheckType(*weight, JsonNode::Type::kNumber, field + ".weight");
        if (!status.ok()) return status;
        if (!(weight->number >= 0.0 && weight->number <= kMaxWeight)) {
          return Error(*weight, field + ".weight: expected in [0, 1e6]");
        }
        attachment.weight = weight->number;
      }
      total_weight += attachment.weight;
      const JsonNode* offset = a.Find("offset");
      if (offset == nullptr) return Error(a, field + ": missing \"offset\"");
      if (!offset->is_array() || offset->items.size() != 3) {
        return Error(*offset, field + ".offset: expected an array of 3 numbers [x, y, z]");
      }
      for (int i = 0; i < 3; ++i) {
        const JsonNode& value = offset->items[i];
        if (!value.is_number()) {
          return Error(value, field + ".offset[" + std::to_string(i) + "]: expected number, got " +
                                  JsonTypeName(value.type));
        }
        // As marker coordinates (MarkerTrajectories::kMaxCoordinate): a sum of such
        // offsets stays finite, and in float (C3D) range, through FK.
        if (!(std::abs(value.number) <= MarkerTrajectories::kMaxCoordinate)) {
          return Error(value, field + ".offset[" + std::to_string(i) + "]: beyond +-1e9");
        }
        attachment.offset[i] = value.number * factor_;
      }
      if (!attachment.offset.allFinite()) return Error(*offset, field + ".offset: out of range after unit conversion");
      spec->attachments.push_back(attachment);
    }
    if (!(total_weight > 0.0)) return Error(*attachments, "attachments: weights sum to zero");
    return Status::Ok();
  }

  const std::string& file_name_;
  const Skeleton& skeleton_;
  std::string context_;  // "markers[3]: 'LBWT': " while reading a marker.
  double factor_ = 1.0;  // File units -> skeleton units.
};

}  // namespace

Status ParseMarkerSet(std::string_view text, const std::string& file_name,
                      const Skeleton& skeleton, MarkerSet* marker_set) {
  JsonNode root;
  Status status = ParseJson(text, file_name, &root);
  if (!status.ok()) return status;
  return Interpreter(file_name, skeleton).Run(root, marker_set);
}

Status InterpretMarkerSet(const JsonNode& root, const std::string& file_name, const Skeleton& skeleton,
                          MarkerSet* marker_set) {
  return Interpreter(file_name, skeleton).Run(root, marker_set);
}

Status ReadMarkerSet(const std::string& path, const Skeleton& skeleton, MarkerSet* marker_set) {
  std::string text;
  Status status = ReadFileToString(path, &text);
  if (!status.ok()) return status;
  return ParseMarkerSet(text, path, skeleton, marker_set);
}

std::string FormatMarkerSet(const Skeleton& skeleton, const MarkerSet& marker_set,
                            const std::string& skeleton_description) {
  // Version 2 adds the per-marker "solve_weight"; a set without learned weights stays 1.
  bool weighted = false;
  for (int m = 0; m < marker_set.num_markers(); ++m) weighted |= marker_set.marker(m).solve_weight != 1.0;
  std::string out = "{\n  \"format\": \"" + std::string(kFormat) + "\",\n  \"version\": " + (weighted ? "2" : "1") + ",\n";
  out += "  \"units\": " + JsonQuote(skeleton.unit().name) + ",\n";
  if (!skeleton_description.empty()) out += "  \"skeleton\": " + JsonQuote(skeleton_description) + ",\n";
  out += "  \"markers\": [";
  for (int m = 0; m < marker_set.num_markers(); ++m) {
    const MarkerSpec& spec = marker_set.marker(m);
    out += m == 0 ? "\n    " : ",\n    ";
    out += "{\"label\": " + JsonQuote(spec.label) + ", \"attachments\": [";
    for (size_t k = 0; k < spec.attachments.size(); ++k) {
      const MarkerAttachment& a = spec.attachments[k];
      out += k == 0 ? "" : ", ";
      out += "{\"joint\": " + JsonQuote(skeleton.name(a.joint)) +
             ", \"weight\": " + JsonValue(a.weight).text() + ", \"offset\": [" +
             JsonValue(a.offset.x()).text() + ", " + JsonValue(a.offset.y()).text() + ", " +
             JsonValue(a.offset.z()).text() + "]}";
    }
    out += "]";
    // Written only when learned (marker_weights.h): files without it read as weight 1.
    if (spec.solve_weight != 1.0) out += ", \"solve_weight\": " + JsonValue(spec.solve_weight).text();
    out += "}";
  }
  out += marker_set.num_markers() > 0 ? "\n  ]\n}\n" : "]\n}\n";
  return out;
}

Status WriteMarkerSet(const std::string& path, const Skeleton& skeleton,
                      const MarkerSet& marker_set, const std::string& skeleton_description) {
  for (int m = 0; m < marker_set.num_markers(); ++m) {
    for (const MarkerAttachment& a : marker_set.marker(m).attachments) {
      if (a.joint < 0 || a.joint >= skeleton.num_joints()) {
        return Status::Error(path + ": marker " + QuoteToken(marker_set.label(m)) + " names joint index " +
                             std::to_string(a.joint) + ", not in the skeleton");
      }
    }
  }
  return WriteFileAtomically(path, FormatMarkerSet(skeleton, marker_set, skeleton_description));
}

}  // namespace mocapsolve
