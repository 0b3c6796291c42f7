#include "problems/retarget/humanoid_roles.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "problems/retarget/joint_map.h"

namespace mocapsolve {
namespace {

// Name split into lower-case words at non-alphanumerics, case changes and digits
// ("mixamorig:LeftUpLeg" -> mixamorig left up leg, "Foot.L_end" -> foot l end).
std::vector<std::string> Words(const std::string& name) {
  std::vector<std::string> words;
  std::string word;
  auto flush = [&] {
    if (!word.empty()) words.push_back(word);
    word.clear();
  };
  for (size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (!std::isalpha(c)) {
      flush();
      continue;
    }
    const bool upper = std::isupper(c);
    const bool prev_lower = i > 0 && std::islower(static_cast<unsigned char>(name[i - 1]));
    const bool next_lower = i + 1 < name.size() && std::islower(static_cast<unsigned char>(name[i + 1]));
    const bool prev_upper = i > 0 && std::isupper(static_cast<unsigned char>(name[i - 1]));
    if (upper && (prev_lower || (prev_upper && next_lower))) flush();  // "LHip" -> L Hip.
    word.push_back(static_cast<char>(std::tolower(c)));
  }
  flush();
  return words;
}

bool IsEndName(const std::string& name) {
  for (const std::string& w : Words(name)) {
    if (w == "end" || w == "top" || w == "tip" || w == "nub" || w == "null" || w == "effector") return true;
  }
  return false;
}

class Finder {
 public:
  Finder(const Skeleton& skeleton, const Vector3dVector& p, const std::vector<bool>& weighted)
      : s_(skeleton), p_(p), weighted_(weighted), children_(skeleton.num_joints()) {
    for (int j = 1; j < s_.num_joints(); ++j) children_[s_.parent(j)].push_back(j);
    // Weights tell end bones only where most joints carry some (not where rigid parts
    // hang from bones unskinned, as RobotExpressive's).
    const int carrying = static_cast<int>(std::count(weighted.begin(), weighted.end(), true));
    use_weights_ = !weighted.empty() && 2 * carrying >= s_.num_joints();
    // Helpers (unskinned duplicate chains) wherever some joint carries weight: a full Rigify
    // export has several times more control and ORG-/MCH- bones than DEF- ones.
    helper_weights_ = !weighted.empty() && carrying > 0;
    subtree_weighted_.assign(s_.num_joints(), false);
    for (int j = s_.num_joints() - 1; helper_weights_ && j >= 0; --j) {
      subtree_weighted_[j] = subtree_weighted_[j] || weighted_[j];
      if (j > 0 && subtree_weighted_[j]) subtree_weighted_[s_.parent(j)] = true;
    }
  }

  HumanoidRoles Run();

 private:
  int Size(int j) const { return s_.subtree_end(j) - j; }
  // Farthest joint of subtree(c) from `from`.
  double Reach(int c, int from) const {
    double r = 0.0;
    for (int k = c; k < s_.subtree_end(c); ++k) r = std::max(r, (p_[k] - p_[from]).norm());
    return r;
  }
  bool IsEnd(int j) const {
    if (!children_[j].empty()) return false;
    if (IsEndName(s_.name(j))) return true;
    return use_weights_ && !weighted_[j];
  }
  bool Pair(int a, int b, int parent) const {
    const int sa = Size(a), sb = Size(b);
    if (sa < 2 || sb < 2) return false;
    if (std::abs(sa - sb) > std::max(1, static_cast<int>(0.25 * std::max(sa, sb)))) return false;
    const double ra = Reach(a, parent), rb = Reach(b, parent);
    return ra > 0.0 && rb > 0.0 && ra / rb >= 0.6 && ra / rb <= 1.0 / 0.6;
  }
  // The best pair among `candidates` (most joints), or false.
  bool BestPair(const std::vector<int>& candidates, int parent, int* a, int* b) const {
    int best = -1;
    for (size_t i = 0; i < candidates.size(); ++i) {
      for (size_t k = i + 1; k < candidates.size(); ++k) {
        if (!Pair(candidates[i], candidates[k], parent)) continue;
        const int size = Size(candidates[i]) + Size(candidates[k]);
        if (size > best) best = size, *a = candidates[i], *b = candidates[k];
      }
    }
    return best >= 0;
  }
  // A helper chain (IK/FK duplicate, control): named so, or carrying no weight where
  // weights tell.
  bool IsHelper(int j) const {
    for (const std::string& w : Words(s_.name(j))) {
      if (w == "ik" || w == "mch" || w == "ctrl" || w == "pole" || w == "target" || w == "helper") return true;
    }
    return helper_weights_ && !subtree_weighted_[j];
  }
  // Children of j that are no helpers (all of them if only helpers).
  std::vector<int> Limbs(int j) const {
    std::vector<int> limbs;
    for (int k : children_[j]) {
      if (!IsHelper(k)) limbs.push_back(k);
    }
    return limbs.empty() ? children_[j] : limbs;
  }
  std::vector<int> MainChain(int c) const {
    std::vector<int> chain = {c};
    for (int j = c; !children_[j].empty();) {
      int next = children_[j][0];
      for (int k : children_[j]) {
        if (IsHelper(k) != IsHelper(next)) {
          if (IsHelper(next)) next = k;
          continue;
        }
        if (Size(k) > Size(next) || (Size(k) == Size(next) && Reach(k, j) > Reach(next, j) + 1e-12)) next = k;
      }
      chain.push_back(next);
      j = next;
    }
    while (chain.size() > 1 && IsEnd(chain.back())) chain.pop_back();
    return chain;
  }
  // The neck chain: also without a last leaf that has siblings (a head top beside eyes).
  std::vector<int> HeadChain(int c) const {
    std::vector<int> chain = MainChain(c);
    if (chain.size() > 2 && children_[chain.back()].empty() && children_[chain[chain.size() - 2]].size() >= 2) {
      chain.pop_back();
    }
    return chain;
  }
  // Limb roles along a chain: [0] upper (thigh/upper arm), [1] lower, [2] end (foot/hand),
  // [3] toes, [4] before (clavicle); -1 where absent. False if the chain has no segment.
  // The upper joint starts a long segment (>= 0.6 of the longest); of those followed by
  // another long one, the one whose upper/lower length ratio is nearest `ratio` (log).
  bool LimbRoles(const std::vector<int>& chain, double ratio, int out[5]) const {
    for (int i = 0; i < 5; ++i) out[i] = -1;
    std::vector<double> length;
    for (size_t i = 0; i + 1 < chain.size(); ++i) length.push_back((p_[chain[i + 1]] - p_[chain[i]]).norm());
    if (length.empty()) return false;
    const double longest = *std::max_element(length.begin(), length.end());
    if (!(longest > 0.0)) return false;
    int pick = -1;
    bool paired = false;
    double best = 0.0;
    for (size_t i = 0; i < std::min<size_t>(length.size(), 2); ++i) {  // At most a clavicle before.
      if (length[i] < 0.35 * longest) continue;
      if (pick < 0) pick = static_cast<int>(i);  // The first long one, if no pair fits.
      if (i + 1 >= length.size() || length[i + 1] < 0.35 * longest) continue;
      const double miss = std::abs(std::log(length[i] / length[i + 1] / ratio));
      if (!paired || miss < best) best = miss, pick = static_cast<int>(i), paired = true;
    }
    if (pick < 0) return false;
    const size_t i = static_cast<size_t>(pick);
    out[0] = chain[i];
    out[1] = chain[i + 1];
    if (i + 2 < chain.size()) out[2] = chain[i + 2];
    if (i + 3 < chain.size()) out[3] = chain[i + 3];
    if (i >= 1) out[4] = chain[i - 1];
    return true;
  }
  // +1: a is left of b; -1: b is left of a; 0: undecided. Sets *evidence.
  int SideOf(int a, int b, int ja, int jb, const Eigen::Vector3d& left, double scale, double* certainty) const {
    if (left.squaredNorm() > 0.5) {
      const double d = (p_[ja] - p_[jb]).dot(left);
      if (std::abs(d) > 0.02 * scale) {
        *certainty = 1.0;
        return d > 0 ? 1 : -1;
      }
    }
    int votes = 0;  // > 0: a is left.
    for (int k = a; k < s_.subtree_end(a); ++k) votes -= NameSide(s_.name(k));
    for (int k = b; k < s_.subtree_end(b); ++k) votes += NameSide(s_.name(k));
    if (votes != 0) {
      *certainty = 0.75;
      return votes > 0 ? 1 : -1;
    }
    *certainty = 0.5;
    return 1;
  }

  const Skeleton& s_;
  const Vector3dVector& p_;
  const std::vector<bool>& weighted_;
  std::vector<std::vector<int>> children_;
  bool use_weights_ = false;
  bool helper_weights_ = false;
  std::vector<bool> subtree_weighted_;  // Some joint of subtree(j) carries weight.
};

HumanoidRoles Finder::Run() {
  HumanoidRoles out;
  struct Choice {
    int pelvis = -1, chest = -1, leg_a = -1, leg_b = -1, arm_a = -1, arm_b = -1, neck = -1, coverage = -1;
  };
  Choice best;
  std::string rejected;
  for (int pelvis = 0; pelvis < s_.num_joints(); ++pelvis) {
    const std::vector<int>& kids = children_[pelvis];
    if (kids.size() < 3) continue;
    for (int spine : kids) {
      // The chest: first joint of the spine branch with a pair of arms and a neck.
      Choice c;
      for (int j = spine; j < s_.subtree_end(spine) && c.chest < 0; ++j) {
        const std::vector<int> limbs = Limbs(j);
        if (limbs.size() < 3) continue;
        int a, b;
        if (!BestPair(limbs, j, &a, &b)) continue;
        int neck = -1;
        for (int k : limbs) {
          if (k != a && k != b && (neck < 0 || Size(k) > Size(neck))) neck = k;
        }
        c.chest = j, c.arm_a = a, c.arm_b = b, c.neck = neck;
      }
      if (c.chest < 0) continue;
      std::vector<int> others;
      for (int k : Limbs(pelvis)) {
        if (k != spine) others.push_back(k);
      }
      if (!BestPair(others, pelvis, &c.leg_a, &c.leg_b)) continue;
      c.pelvis = pelvis;
      // Geometry: the legs point away from the head.
      const std::vector<int> head_chain = HeadChain(c.neck);
      const Eigen::Vector3d up = p_[head_chain.back()] - p_[pelvis];
      const Eigen::Vector3d legs =
          p_[MainChain(c.leg_a).back()] + p_[MainChain(c.leg_b).back()] - 2.0 * p_[pelvis];
      const double cosine = up.norm() > 0 && legs.norm() > 0 ? up.dot(legs) / (up.norm() * legs.norm()) : 1.0;
      if (cosine > std::cos(120.0 * M_PI / 180.0)) {
        rejected = "two limb pairs at '" + s_.name(pelvis) + "' and '" + s_.name(c.chest) + "', but the legs are " +
                   std::to_string(static_cast<int>(std::lround(std::acos(std::clamp(cosine, -1.0, 1.0)) * 180 / M_PI))) +
                   " degrees from the head (a humanoid's are > 120)";
        continue;
      }
      c.coverage = Size(c.leg_a) + Size(c.leg_b) + Size(spine);
      if (c.coverage > best.coverage) best = c;
    }
  }
  if (best.pelvis < 0) {
    out.why_not = rejected.empty() ? "no joint where a pair of legs and a spine with a pair of arms and a neck branch"
                                   : rejected;
    return out;
  }
  out.humanoid = true;
  const Eigen::Vector3d pelvis_p = p_[best.pelvis];
  const std::vector<int> neck_chain = HeadChain(best.neck);
  Eigen::Vector3d up = p_[neck_chain.back()] - pelvis_p;
  const double scale = std::max(up.norm(), 1e-12);
  up /= scale;

  int leg[2][5], arm[2][5];
  const bool leg_ok[2] = {LimbRoles(MainChain(best.leg_a), 1.05, leg[0]), LimbRoles(MainChain(best.leg_b), 1.05, leg[1])};
  const bool arm_ok[2] = {LimbRoles(MainChain(best.arm_a), 1.2, arm[0]), LimbRoles(MainChain(best.arm_b), 1.2, arm[1])};
  // Forward: foot->toes, else the knees' bulge, horizontal.
  auto horizontal = [&](const Eigen::Vector3d& v) { return Eigen::Vector3d(v - v.dot(up) * up); };
  Eigen::Vector3d forward = Eigen::Vector3d::Zero();
  for (int i = 0; i < 2; ++i) {
    if (!leg_ok[i] || leg[i][2] < 0 || leg[i][3] < 0) continue;
    const Eigen::Vector3d foot = p_[leg[i][3]] - p_[leg[i][2]];  // Used when it lies along the floor.
    if (std::abs(foot.normalized().dot(up)) < 0.7) forward += horizontal(foot);
  }
  if (forward.norm() < 0.02 * scale) {
    forward.setZero();
    for (int i = 0; i < 2; ++i) {
      if (leg_ok[i] && leg[i][2] >= 0) forward += horizontal(p_[leg[i][1]] - 0.5 * (p_[leg[i][0]] + p_[leg[i][2]]));
    }
  }
  if (forward.norm() < 0.02 * scale) {  // Elbows flex forward: the forearms' sum, sides cancelling.
    forward.setZero();
    double spread = 0.0, length = 0.0;
    for (int i = 0; i < 2; ++i) {
      if (!arm_ok[i] || arm[i][2] < 0) continue;
      const Eigen::Vector3d forearm = p_[arm[i][2]] - p_[arm[i][1]];
      forward += horizontal(forearm);
      spread += horizontal(forearm).norm();
      length += forearm.norm();
    }
    // Flexed (not hanging: >= 30 % horizontal) and pointing the same way (>= 25 %).
    if (spread < 0.3 * length || forward.norm() < 0.25 * spread) forward.setZero();
  }
  // Geometry tells sides only in a standing pose: each leg within 35 degrees of down.
  bool standing = true;
  for (int i = 0; i < 2; ++i) {
    if (!leg_ok[i]) continue;
    const Eigen::Vector3d leg_vector = p_[leg[i][2] >= 0 ? leg[i][2] : leg[i][1]] - p_[leg[i][0]];
    if (leg_vector.norm() > 0 && -leg_vector.normalized().dot(up) < std::cos(35.0 * M_PI / 180.0)) standing = false;
  }
  Eigen::Vector3d left = Eigen::Vector3d::Zero();
  if (standing && forward.norm() >= 0.01 * scale) left = up.cross(forward.normalized());
  double leg_certainty = 0.5, arm_certainty = 0.5;
  const int leg_side = leg_ok[0] && leg_ok[1]
                           ? SideOf(best.leg_a, best.leg_b, leg[0][0], leg[1][0], left, scale, &leg_certainty)
                           : SideOf(best.leg_a, best.leg_b, best.leg_a, best.leg_b, left, scale, &leg_certainty);
  const int arm_side = arm_ok[0] && arm_ok[1]
                           ? SideOf(best.arm_a, best.arm_b, arm[0][0], arm[1][0], left, scale, &arm_certainty)
                           : SideOf(best.arm_a, best.arm_b, best.arm_a, best.arm_b, left, scale, &arm_certainty);
  out.side_certainty = std::min(leg_certainty, arm_certainty);
  out.side_evidence = out.side_certainty == 1.0 ? "geometry" : out.side_certainty == 0.75 ? "names" : "guessed";

  auto add = [&](const std::string& role, int j) {
    if (j >= 0) out.roles.emplace_back(role, j);
  };
  add("pelvis", best.pelvis);
  std::vector<int> spine;
  for (int j = s_.parent(best.chest); j != best.pelvis && j >= 0; j = s_.parent(j)) spine.push_back(j);
  std::reverse(spine.begin(), spine.end());
  for (size_t i = 0; i < spine.size(); ++i) add("spine_" + std::to_string(i + 1), spine[i]);
  add("chest", best.chest);
  if (neck_chain.size() >= 2) add("neck", neck_chain.front());
  add("head", neck_chain.back());
  for (const char* side : {"left", "right"}) {
    const bool is_left = std::string(side) == "left";
    const int ai = (arm_side > 0) == is_left ? 0 : 1;
    const int li = (leg_side > 0) == is_left ? 0 : 1;
    const std::string prefix = std::string(side) + "_";
    if (arm_ok[ai]) {
      add(prefix + "clavicle", arm[ai][4]);
      add(prefix + "upper_arm", arm[ai][0]);
      add(prefix + "forearm", arm[ai][1]);
      add(prefix + "hand", arm[ai][2]);
    }
    if (leg_ok[li]) {
      add(prefix + "thigh", leg[li][0]);
      add(prefix + "shin", leg[li][1]);
      add(prefix + "foot", leg[li][2]);
      add(prefix + "toes", leg[li][3]);
    }
  }
  // Template order.
  const std::vector<std::string> order = HumanoidRoleNames(static_cast<int>(spine.size()));
  std::stable_sort(out.roles.begin(), out.roles.end(), [&](const auto& x, const auto& y) {
    return std::find(order.begin(), order.end(), x.first) < std::find(order.begin(), order.end(), y.first);
  });
  return out;
}

}  // namespace

int HumanoidRoles::Find(const std::string& role) const {
  for (const auto& [name, joint] : roles) {
    if (name == role) return joint;
  }
  return -1;
}

std::string HumanoidRoles::RoleList() const {
  std::string list;
  for (const auto& [name, joint] : roles) list += (list.empty() ? "" : ", ") + name;
  return list.empty() ? "none" : list;
}

std::vector<std::string> HumanoidRoleNames(int spine_joints) {
  std::vector<std::string> names = {"pelvis"};
  for (int i = 1; i <= spine_joints; ++i) names.push_back("spine_" + std::to_string(i));
  for (const char* role : {"chest", "neck", "head"}) names.push_back(role);
  for (const char* side : {"left_", "right_"}) {
    for (const char* role : {"clavicle", "upper_arm", "forearm", "hand", "thigh", "shin", "foot", "toes"}) {
      names.push_back(std::string(side) + role);
    }
  }
  return names;
}

int NameSide(const std::string& name) {
  int side = 0;
  for (const std::string& w : Words(name)) {
    if (w == "l" || w == "left" || w == "lft") side = -1;
    if (w == "r" || w == "right" || w == "rgt") side = 1;
  }
  if (side != 0) return side;
  const std::string canonical = CanonicalJointName(NormalizeJointName(name));
  if (canonical.rfind("left", 0) == 0) return -1;
  if (canonical.rfind("right", 0) == 0) return 1;
  return 0;
}

HumanoidRoles FindHumanoidRoles(const Skeleton& skeleton, const Vector3dVector& world_positions,
                                const std::vector<bool>& weighted) {
  if (static_cast<int>(world_positions.size()) != skeleton.num_joints() ||
      (!weighted.empty() && static_cast<int>(weighted.size()) != skeleton.num_joints())) {
    HumanoidRoles out;
    out.why_not = "positions do not fit the skeleton";
    return out;
  }
  return Finder(skeleton, world_positions, weighted).Run();
}

std::vector<int> BodyParts(const Skeleton& skeleton, const HumanoidRoles& roles) {
  std::vector<int> part(skeleton.num_joints(), -1);
  for (size_t r = 0; r < roles.roles.size(); ++r) {
    const int j = roles.roles[r].second;
    if (j >= 0 && j < skeleton.num_joints()) part[j] = static_cast<int>(r);
  }
  for (int j = 0; j < skeleton.num_joints(); ++j) {  // Parents come first.
    if (part[j] < 0 && skeleton.parent(j) >= 0) part[j] = part[skeleton.parent(j)];
  }
  return part;
}

}  // namespace mocapsolve
