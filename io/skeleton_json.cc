#include "io/skeleton_json.h"

#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "io/input_limits.h"
#include "io/json_writer.h"
#include "kinematics/quote_token.h"

namespace mocapsolve {
namespace {

const char* const kChannelNames[] = {"Xposition", "Yposition", "Zposition",
                                     "Xrotation", "Yrotation", "Zrotation"};

class SkeletonInterpreter {
 public:
  SkeletonInterpreter(const std::string& file_name, const std::string& field)
      : file_name_(file_name), field_(field) {}

  Status Error(const JsonNode& node, const std::string& message) const {
    return Status::Error(node.Where(file_name_) + ": " + context_ + message);
  }

  Status Keys(const JsonNode& object, const std::set<std::string>& allowed) const {
    if (const auto* member = FindUnknownKey(object, allowed)) {
      return Error(member->second, "unknown key '" + member->first + "' (known: " + KeyList(allowed) + ")");
    }
    return Status::Ok();
  }

  Status Vector(const JsonNode* node, const JsonNode& owner, const std::string& name, int size,
                std::vector<double>* values) const {
    if (node == nullptr) return Error(owner, "missing \"" + name + "\"");
    if (!node->is_array() || static_cast<int>(node->items.size()) != size) {
      return Error(*node, name + ": expected an array of " + std::to_string(size) + " numbers");
    }
    values->clear();
    for (const JsonNode& item : node->items) {
      if (!item.is_number()) return Error(item, name + ": expected numbers");
      if (name == "offset" && !(std::abs(item.number) <= kMaxCoordinate)) {  // io/input_limits.h
        return Error(item, name + ": " + ShortNumber(item.number) + " is beyond +-" + ShortNumber(kMaxCoordinate));
      }
      values->push_back(item.number);
    }
    return Status::Ok();
  }

  Status Run(const JsonNode& root, Skeleton* skeleton) {
    context_ = field_ + ": ";
    if (!root.is_object()) return Error(root, "expected an object, got " + std::string(JsonTypeName(root.type)));
    Status status = Keys(root, {"units", "metres_per_unit", "joints", "end_sites"});
    if (!status.ok()) return status;
    LengthUnit unit;
    const JsonNode* units = root.Find("units");
    if (units == nullptr || !units->is_string()) return Error(units ? *units : root, "units: expected a string");
    unit.name = units->string;
    const JsonNode* metres = root.Find("metres_per_unit");
    if (metres == nullptr || !metres->is_number() || !(metres->number >= 0.0) || !std::isfinite(metres->number)) {
      return Error(metres ? *metres : root, "metres_per_unit: expected a number >= 0 (0: unknown)");
    }
    unit.metres_per_unit = metres->number;
    const JsonNode* joints = root.Find("joints");
    if (joints == nullptr || !joints->is_array() || joints->items.empty()) {
      return Error(joints ? *joints : root, "joints: expected a non-empty array");
    }
    std::vector<JointSpec> specs;
    for (size_t j = 0; j < joints->items.size(); ++j) {
      context_ = field_ + ".joints[" + std::to_string(j) + "]: ";
      JointSpec spec;
      status = ReadJoint(joints->items[j], specs, &spec);
      if (!status.ok()) return status;
      specs.push_back(std::move(spec));
    }
    std::vector<EndSite> sites;
    if (const JsonNode* end_sites = root.Find("end_sites")) {
      if (!end_sites->is_array()) return Error(*end_sites, "end_sites: expected an array");
      for (size_t e = 0; e < end_sites->items.size(); ++e) {
        context_ = field_ + ".end_sites[" + std::to_string(e) + "]: ";
        const JsonNode& node = end_sites->items[e];
        if (!node.is_object()) return Error(node, "expected an object");
        status = Keys(node, {"name", "parent", "offset"});
        if (!status.ok()) return status;
        EndSite site;
        const JsonNode* name = node.Find("name");
        if (name == nullptr || !name->is_string()) return Error(name ? *name : node, "name: expected a string");
        site.name = name->string;
        status = Parent(node, specs, &site.parent);
        if (!status.ok()) return status;
        if (site.parent < 0) return Error(node, "parent: an end site needs a joint");
        std::vector<double> v;
        status = Vector(node.Find("offset"), node, "offset", 3, &v);
        if (!status.ok()) return status;
        site.offset = Eigen::Vector3d(v[0], v[1], v[2]);
        sites.push_back(std::move(site));
      }
    }
    context_ = field_ + ": ";
    Skeleton result;
    status = Skeleton::Create(std::move(specs), std::move(sites), unit, &result);
    if (!status.ok()) return Error(root, status.message());
    *skeleton = std::move(result);
    return Status::Ok();
  }

 private:
  Status Parent(const JsonNode& node, const std::vector<JointSpec>& earlier, int* parent) const {
    const JsonNode* p = node.Find("parent");
    if (p == nullptr) return Error(node, "missing \"parent\" (null for the root)");
    *parent = -1;
    if (p->is_null()) return Status::Ok();
    if (!p->is_string()) return Error(*p, "parent: expected a joint name or null");
    for (size_t i = 0; i < earlier.size(); ++i) {
      if (earlier[i].name == p->string) *parent = static_cast<int>(i);
    }
    if (*parent < 0) return Error(*p, "parent: unknown joint '" + p->string + "' (parents come first)");
    return Status::Ok();
  }

  Status ReadJoint(const JsonNode& node, const std::vector<JointSpec>& earlier, JointSpec* spec) {
    if (!node.is_object()) return Error(node, "expected an object");
    const JsonNode* name = node.Find("name");
    if (name == nullptr || !name->is_string()) return Error(name ? *name : node, "name: expected a string");
    spec->name = name->string;
    context_ += "'" + spec->name + "': ";
    Status status = Keys(node, {"name", "parent", "offset", "rest_rotation", "channels", "rotation_axes",
                                "rotation_limits"});
    if (!status.ok()) return status;
    status = Parent(node, earlier, &spec->parent);
    if (!status.ok()) return status;
    std::vector<double> v;
    status = Vector(node.Find("offset"), node, "offset", 3, &v);
    if (!status.ok()) return status;
    spec->offset = Eigen::Vector3d(v[0], v[1], v[2]);
    if (const JsonNode* rest = node.Find("rest_rotation")) {
      status = Vector(rest, node, "rest_rotation", 4, &v);
      if (!status.ok()) return status;
      spec->rest_rotation = Eigen::Quaterniond(v[0], v[1], v[2], v[3]);
    }
    if (const JsonNode* channels = node.Find("channels")) {
      if (!channels->is_array()) return Error(*channels, "channels: expected an array of names");
      for (const JsonNode& c : channels->items) {
        int found = -1;
        for (int k = 0; k < 6; ++k) {
          if (c.is_string() && c.string == kChannelNames[k]) found = k;
        }
        if (found < 0) return Error(c, "channels: expected Xposition ... Zrotation");
        spec->channels.push_back(static_cast<Channel>(found));
      }
    }
    if (const JsonNode* axes = node.Find("rotation_axes")) {
      if (!axes->is_array()) return Error(*axes, "rotation_axes: expected an array of \"x\", \"y\", \"z\"");
      std::vector<int> list;
      for (const JsonNode& a : axes->items) {
        if (!a.is_string() || a.string.size() != 1 || a.string[0] < 'x' || a.string[0] > 'z') {
          return Error(a, "rotation_axes: expected \"x\", \"y\" or \"z\"");
        }
        list.push_back(a.string[0] - 'x');
      }
      spec->rotation_axes = list;
    }
    if (const JsonNode* limits = node.Find("rotation_limits")) {
      if (!limits->is_array()) return Error(*limits, "rotation_limits: expected an array of [lo, hi]");
      constexpr double kInf = std::numeric_limits<double>::infinity();
      for (const JsonNode& l : limits->items) {
        if (!l.is_array() || l.items.size() != 2 || !(l.items[0].is_number() || l.items[0].is_null()) ||
            !(l.items[1].is_number() || l.items[1].is_null())) {
          return Error(l, "rotation_limits: expected [lo, hi] (radians, null: unbounded)");
        }
        const double lo = l.items[0].is_null() ? -kInf : l.items[0].number;
        const double hi = l.items[1].is_null() ? kInf : l.items[1].number;
        if (!(lo <= hi)) return Error(l, "rotation_limits: lo > hi");
        spec->rotation_limits.emplace_back(lo, hi);
      }
      const size_t axes = spec->rotation_axes ? spec->rotation_axes->size() : 3;
      if (!spec->rotation_limits.empty() && spec->rotation_limits.size() != axes) {
        return Error(*limits, "rotation_limits: expected one [lo, hi] per rotation axis");
      }
    }
    return Status::Ok();
  }

  const std::string& file_name_;
  std::string field_;
  std::string context_;
};

std::string Numbers(std::initializer_list<double> values) {
  std::string out = "[";
  bool first = true;
  for (double v : values) {
    out += (first ? "" : ", ") + JsonValue(v).text();
    first = false;
  }
  return out + "]";
}

}  // namespace

Status InterpretSkeletonJson(const JsonNode& node, const std::string& file_name, const std::string& field,
                             Skeleton* skeleton) {
  return SkeletonInterpreter(file_name, field).Run(node, skeleton);
}

std::string FormatSkeletonJson(const Skeleton& skeleton, int indent) {
  const std::string pad(indent, ' ');
  std::string out = "{\n" + pad + "  \"units\": " + JsonQuote(skeleton.unit().name) + ",\n" + pad +
                    "  \"metres_per_unit\": " + JsonValue(skeleton.unit().metres_per_unit).text() + ",\n" + pad +
                    "  \"joints\": [";
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const JointSpec& spec = skeleton.joint(j);
    out += (j == 0 ? "\n" : ",\n") + pad + "    {\"name\": " + JsonQuote(spec.name) + ", \"parent\": " +
           (spec.parent < 0 ? std::string("null") : JsonQuote(skeleton.name(spec.parent))) + ", \"offset\": " +
           Numbers({spec.offset.x(), spec.offset.y(), spec.offset.z()});
    const Eigen::Quaterniond& q = spec.rest_rotation;
    if (!q.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs(), 0.0)) {
      out += ", \"rest_rotation\": " + Numbers({q.w(), q.x(), q.y(), q.z()});
    }
    if (!spec.channels.empty()) {
      out += ", \"channels\": [";
      for (size_t c = 0; c < spec.channels.size(); ++c) {
        out += (c ? ", \"" : "\"") + std::string(kChannelNames[static_cast<int>(spec.channels[c])]) + "\"";
      }
      out += "]";
    }
    if (spec.rotation_axes) {
      out += ", \"rotation_axes\": [";
      for (size_t a = 0; a < spec.rotation_axes->size(); ++a) {
        out += (a ? ", \"" : "\"") + std::string(1, static_cast<char>('x' + (*spec.rotation_axes)[a])) + "\"";
      }
      out += "]";
    }
    if (!spec.rotation_limits.empty()) {
      out += ", \"rotation_limits\": [";
      for (size_t l = 0; l < spec.rotation_limits.size(); ++l) {
        out += (l ? ", " : "") + Numbers({spec.rotation_limits[l].first, spec.rotation_limits[l].second});
      }
      out += "]";
    }
    out += "}";
  }
  out += "\n" + pad + "  ],\n" + pad + "  \"end_sites\": [";
  const std::vector<EndSite>& sites = skeleton.end_sites();
  for (size_t e = 0; e < sites.size(); ++e) {
    out += (e == 0 ? "\n" : ",\n") + pad + "    {\"name\": " + JsonQuote(sites[e].name) + ", \"parent\": " +
           JsonQuote(skeleton.name(sites[e].parent)) + ", \"offset\": " +
           Numbers({sites[e].offset.x(), sites[e].offset.y(), sites[e].offset.z()}) + "}";
  }
  out += sites.empty() ? "]\n" + pad + "}" : "\n" + pad + "  ]\n" + pad + "}";
  return out;
}

}  // namespace mocapsolve
