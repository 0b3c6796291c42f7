#include "problems/retarget/joint_map.h"

#include <cctype>
#include <map>

namespace mocapsolve {
namespace {

const std::map<std::string, std::string>& Synonyms() {
  static const std::map<std::string, std::string>* table = [] {
    auto* t = new std::map<std::string, std::string>{
        {"root", "hips"},        {"pelvis", "hips"},      {"hip", "hips"},
        {"lowerback", "spine"},  {"abdomen", "spine"},    {"upperback", "spine1"},
        {"torso", "spine1"},     {"thorax", "spine2"},    {"chest", "spine2"},
        {"lowerneck", "neck"},   {"upperneck", "neck1"},
    };
    // Per side: canonical Mixamo suffix -> the other spellings (with {s} = side word).
    const std::vector<std::pair<std::string, std::vector<std::string>>> sided = {
        {"shoulder", {"clavicle", "collar"}},
        {"arm", {"upperarm", "humerus"}},
        {"forearm", {"lowerarm", "radius", "elbow"}},
        {"hand", {"wrist"}},
        {"upleg", {"upperleg", "thigh", "femur"}},
        {"leg", {"lowerleg", "shin", "calf", "tibia", "knee"}},
        {"foot", {"ankle"}},
        {"toebase", {"toe", "toes"}},
    };
    const std::vector<std::pair<std::string, std::vector<std::string>>> sides = {
        {"left", {"left", "l"}}, {"right", {"right", "r"}}};
    for (const auto& [side, spellings] : sides) {
      for (const auto& [canonical, others] : sided) {
        std::vector<std::string> names = others;
        names.push_back(canonical);
        for (const std::string& name : names) {
          for (const std::string& s : spellings) {
            t->emplace(s + name, side + canonical);  // lfemur, leftthigh
            t->emplace(name + s, side + canonical);  // thighl (Thigh.L), upperarml
          }
        }
      }
    }
    // Mixamo's own names map to themselves; "leftarm" is also "larm".
    (*t)["lwrist"] = "lefthand";
    (*t)["rwrist"] = "righthand";
    return t;
  }();
  return *table;
}

}  // namespace

int JointMap::num_mapped() const {
  int n = 0;
  for (int t : target_of_source) n += t >= 0 ? 1 : 0;
  return n;
}

std::string NormalizeJointName(const std::string& name) {
  const size_t cut = name.find_last_of(":|");
  std::string out;
  for (size_t i = cut == std::string::npos ? 0 : cut + 1; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (std::isalnum(c)) out.push_back(static_cast<char>(std::tolower(c)));
  }
  return out;
}

std::string CanonicalJointName(const std::string& normalized) {
  const auto it = Synonyms().find(normalized);
  return it == Synonyms().end() ? normalized : it->second;
}

Status BuildJointMap(const Skeleton& source, const Skeleton& target,
                     const std::vector<std::pair<std::string, std::string>>& overrides,
                     JointMap* map) {
  JointMap out;
  out.target_of_source.assign(source.num_joints(), -1);
  out.source_of_target.assign(target.num_joints(), -1);
  auto link = [&](int s, int t) {
    if (out.target_of_source[s] >= 0) out.source_of_target[out.target_of_source[s]] = -1;
    if (out.source_of_target[t] >= 0) out.target_of_source[out.source_of_target[t]] = -1;
    out.target_of_source[s] = t;
    out.source_of_target[t] = s;
  };
  for (int pass = 0; pass < 2; ++pass) {
    std::map<std::string, int> target_keys;
    for (int t = target.num_joints() - 1; t >= 0; --t) {  // The first of equal keys wins.
      if (out.source_of_target[t] >= 0) continue;
      const std::string n = NormalizeJointName(target.name(t));
      if (!n.empty()) target_keys[pass == 0 ? n : CanonicalJointName(n)] = t;
    }
    for (int s = 0; s < source.num_joints(); ++s) {
      if (out.target_of_source[s] >= 0) continue;
      const std::string n = NormalizeJointName(source.name(s));
      if (n.empty()) continue;
      const auto it = target_keys.find(pass == 0 ? n : CanonicalJointName(n));
      if (it == target_keys.end() || out.source_of_target[it->second] >= 0) continue;
      link(s, it->second);
    }
  }
  for (const auto& [source_name, target_name] : overrides) {
    const int s = source.FindJoint(source_name);
    if (s < 0) return Status::Error("joint map: the source skeleton has no joint '" + source_name + "'");
    const int t = target.FindJoint(target_name);
    if (t < 0) return Status::Error("joint map: the target skeleton has no joint '" + target_name + "'");
    link(s, t);
  }
  *map = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
