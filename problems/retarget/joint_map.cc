#include "problems/retarget/joint_map.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>

#include "kinematics/forward_kinematics.h"
#include "problems/retarget/own_skeleton.h"

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

JointMapSkeleton StandingSkeleton(const Skeleton& skeleton, const Pose& pose, const SkinnedMesh* mesh,
                                  const Pose& other) {
  JointMapSkeleton out;
  out.skeleton = &skeleton;
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose.rotations.empty() ? RestPose(skeleton) : pose, &fk);
  out.positions = fk.world_positions;
  if (other.rotations.size() == static_cast<size_t>(skeleton.num_joints())) {
    ForwardKinematics(skeleton, other, &fk);
    out.other_positions = fk.world_positions;
  }
  if (mesh != nullptr && mesh->num_joints() == skeleton.num_joints()) {
    out.weighted.assign(skeleton.num_joints(), false);
    for (int v = 0; v < mesh->num_vertices(); ++v) {
      for (int k = mesh->weight_begin(v); k < mesh->weight_end(v); ++k) {
        if (mesh->weight(k) > 0.0) out.weighted[mesh->weight_joint(k)] = true;
      }
    }
  }
  return out;
}

HumanoidRoles FindRoles(const JointMapSkeleton& skeleton) {
  HumanoidRoles roles = FindHumanoidRoles(*skeleton.skeleton, skeleton.positions, skeleton.weighted);
  if (roles.humanoid && roles.side_evidence != "geometry" && !skeleton.other_positions.empty()) {
    HumanoidRoles other = FindHumanoidRoles(*skeleton.skeleton, skeleton.other_positions, skeleton.weighted);
    if (other.humanoid && other.side_evidence == "geometry") return other;
  }
  return roles;
}

std::string JointMap::Found(bool source) const {
  const HumanoidRoles& roles = source ? source_roles : target_roles;
  if (roles.humanoid) return "humanoid (roles: " + roles.RoleList() + ")";
  return "not a humanoid (" + roles.why_not + ")";
}

namespace {

// The role group of each joint: the role, "spine" for spine_i; "" none.
std::vector<std::string> RoleGroups(const HumanoidRoles& roles, int num_joints) {
  std::vector<std::string> groups(num_joints);
  for (const auto& [role, joint] : roles.roles) groups[joint] = role.rfind("spine_", 0) == 0 ? "spine" : role;
  return groups;
}

}  // namespace

Status BuildJointMap(const JointMapSkeleton& source_shape, const JointMapSkeleton& target_shape,
                     const std::vector<std::pair<std::string, std::string>>& overrides,
                     JointMap* map) {
  const Skeleton& source = *source_shape.skeleton;
  const Skeleton& target = *target_shape.skeleton;
  JointMap out;
  out.target_of_source.assign(source.num_joints(), -1);
  out.source_of_target.assign(target.num_joints(), -1);
  out.how_of_source.assign(source.num_joints(), "");
  auto unlink = [&](int s) {
    if (out.target_of_source[s] >= 0) out.source_of_target[out.target_of_source[s]] = -1;
    out.target_of_source[s] = -1;
    out.how_of_source[s].clear();
  };
  auto link = [&](int s, int t, const char* how) {
    unlink(s);
    if (out.source_of_target[t] >= 0) unlink(out.source_of_target[t]);
    out.target_of_source[s] = t;
    out.source_of_target[t] = s;
    out.how_of_source[s] = how;
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
      link(s, it->second, "name");
    }
  }

  out.source_roles = FindRoles(source_shape);
  out.target_roles = FindRoles(target_shape);
  const HumanoidRoles& sr = out.source_roles;
  const HumanoidRoles& tr = out.target_roles;
  // Names that make the source the target's own skeleton (own_skeleton.h: every joint,
  // the hierarchy and the rest offsets) are not second-guessed.
  double own_scale = 1.0;
  const bool names_complete = IsSameSkeleton(source, target, out, &own_scale);
  if (sr.humanoid && tr.humanoid && !names_complete) {
    const std::vector<std::string> sg = RoleGroups(sr, source.num_joints());
    const std::vector<std::string> tg = RoleGroups(tr, target.num_joints());
    for (int s = 0; s < source.num_joints(); ++s) {  // Names that disagree with the structure.
      const int t = out.target_of_source[s];
      if (t >= 0 && !sg[s].empty() && !tg[t].empty() && sg[s] != tg[t]) unlink(s);
    }
    std::vector<int> source_spine, target_spine;
    for (const auto& [role, s] : sr.roles) {
      if (role.rfind("spine_", 0) == 0) {
        source_spine.push_back(s);
        continue;
      }
      const int t = tr.Find(role);
      if (t >= 0 && out.target_of_source[s] != t) link(s, t, "structure");
    }
    for (const auto& [role, t] : tr.roles) {
      if (role.rfind("spine_", 0) == 0) target_spine.push_back(t);
    }
    for (size_t i = 0; i < std::min(source_spine.size(), target_spine.size()); ++i) {
      const int s = source_spine[i], t = target_spine[i];
      if (out.target_of_source[s] < 0 && out.source_of_target[t] < 0) link(s, t, "structure");
    }
    // Name links under role joints that are not linked to each other.
    auto role_above = [](const Skeleton& skeleton, const std::vector<std::string>& groups, int j) {
      for (j = skeleton.parent(j); j >= 0; j = skeleton.parent(j)) {
        if (!groups[j].empty()) return j;
      }
      return -1;
    };
    for (int s = 0; s < source.num_joints(); ++s) {
      const int t = out.target_of_source[s];
      if (t < 0 || out.how_of_source[s] != "name" || !sg[s].empty() || !tg[t].empty()) continue;
      const int as = role_above(source, sg, s), at = role_above(target, tg, t);
      if (as >= 0 && at >= 0 && out.target_of_source[as] != at) unlink(s);
    }
  } else if (!sr.humanoid && !tr.humanoid && source.num_joints() == target.num_joints()) {
    bool same = true;
    for (int j = 0; j < source.num_joints() && same; ++j) same = source.parent(j) == target.parent(j);
    for (int j = 0; j < source.num_joints() && same; ++j) {
      if (out.target_of_source[j] < 0 && out.source_of_target[j] < 0) link(j, j, "topology");
    }
  }

  for (const auto& [source_name, target_name] : overrides) {
    const int s = source.FindJoint(source_name);
    if (s < 0) return Status::Error("joint map: the source skeleton has no joint '" + source_name + "'");
    const int t = target.FindJoint(target_name);
    if (t < 0) return Status::Error("joint map: the target skeleton has no joint '" + target_name + "'");
    link(s, t, "file");
  }

  // The roles of either side, in template order.
  int spine = 0;
  for (const HumanoidRoles* roles : {&sr, &tr}) {
    for (const auto& [role, joint] : roles->roles) {
      if (role.rfind("spine_", 0) == 0) spine = std::max(spine, std::stoi(role.substr(6)));
    }
  }
  int linked = 0;
  for (const std::string& role : HumanoidRoleNames(spine)) {
    JointMapRole entry;
    entry.role = role;
    const int s = sr.Find(role), t = tr.Find(role);
    if (s < 0 && t < 0) continue;
    entry.source = s >= 0 ? s : out.source_of_target[t];
    const int mapped = entry.source >= 0 ? out.target_of_source[entry.source] : -1;
    entry.target = mapped >= 0 ? mapped : t;
    if (mapped >= 0) {
      entry.how = out.how_of_source[entry.source];
      ++linked;
    }
    out.roles.push_back(entry);
  }
  if (sr.humanoid && tr.humanoid) {
    out.confidence = out.roles.empty() ? 0.0
                                       : static_cast<double>(linked) / out.roles.size() *
                                             std::min(sr.side_certainty, tr.side_certainty);
  } else {
    out.confidence = static_cast<double>(out.num_mapped()) / std::max(1, std::max(source.num_joints(), target.num_joints()));
  }
  *map = std::move(out);
  return Status::Ok();
}

std::string JointMapNote(const JointMap& map) {
  std::map<std::string, int> counts;
  for (const std::string& how : map.how_of_source) {
    if (!how.empty()) ++counts[how];
  }
  std::string by;
  for (const char* how : {"name", "structure", "topology", "file"}) {
    if (counts[how] > 0) by += (by.empty() ? "" : ", ") + std::to_string(counts[how]) + " by " + how;
  }
  auto side = [](const HumanoidRoles& roles) {
    return roles.humanoid ? "humanoid (" + std::to_string(roles.roles.size()) + " roles, sides from " +
                                roles.side_evidence + ")"
                          : std::string("not a humanoid");
  };
  char confidence[32];
  std::snprintf(confidence, sizeof confidence, "%.2f", map.confidence);
  return "joint map: " + std::to_string(map.num_mapped()) + " joints (" + (by.empty() ? "none" : by) +
         "); source " + side(map.source_roles) + ", target " + side(map.target_roles) + "; confidence " + confidence;
}

Status BuildJointMap(const Skeleton& source, const Skeleton& target,
                     const std::vector<std::pair<std::string, std::string>>& overrides,
                     JointMap* map) {
  return BuildJointMap(StandingSkeleton(source, Pose(), nullptr), StandingSkeleton(target, Pose(), nullptr),
                       overrides, map);
}

}  // namespace mocapsolve
