#include "problems/marker_solve/held_segments.h"

#include <algorithm>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "problems/retarget/humanoid_roles.h"

namespace mocapsolve {

std::vector<bool> ObservedJoints(const Skeleton& skeleton, const MarkerSet& markers) {
  std::vector<bool> observed(skeleton.num_joints(), false);
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (int j : markers.InfluencingJoints(m)) observed[j] = true;
  }
  return observed;
}

HeldSegments FindHeldSegments(const Skeleton& skeleton, const MarkerSet& markers) {
  const std::vector<bool> observed = ObservedJoints(skeleton, markers);
  HeldSegments held;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (observed[j]) continue;
    ++held.joints;
    const int parent = skeleton.parent(j);
    if (parent < 0 || observed[parent]) held.tops.push_back(skeleton.name(j));
  }
  return held;
}

std::vector<int> AttachableJoints(const Skeleton& skeleton, const MarkerSet& markers) {
  const std::vector<bool> observed = ObservedJoints(skeleton, markers);
  std::vector<bool> excluded(skeleton.num_joints(), false);
  bool any = false;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const int parent = skeleton.parent(j);
    if (observed[j] || (parent >= 0 && !observed[parent])) continue;
    // An end segment (every joint below it a leaf: a hand and its fingers, a foot and its
    // toes) moves nothing but itself after its markers.
    bool end_segment = true;
    for (int k = j + 1; k < skeleton.subtree_end(j); ++k) end_segment = end_segment && skeleton.subtree_end(k) == k + 1;
    if (end_segment) continue;
    for (int k = j; k < skeleton.subtree_end(j); ++k) excluded[k] = true;
    any = true;
  }
  std::vector<int> joints;
  for (int j = 0; any && j < skeleton.num_joints(); ++j) {
    if (!excluded[j]) joints.push_back(j);
  }
  return joints;
}

namespace {

// The joints whose markers observe `role`: a limb segment's subtree; the pelvis' own joint
// and its children that lead to no leg (CMU's lowerback carries LFWT and RFWT), as a leg's
// markers would place the root through the hips but not its tilt or twist.
std::vector<int> SegmentJoints(const Skeleton& skeleton, const HumanoidRoles& roles, const std::string& role) {
  const int j = roles.Find(role);
  std::vector<int> joints;
  if (role != "pelvis") {
    for (int k = j; k < skeleton.subtree_end(j); ++k) joints.push_back(k);
    return joints;
  }
  joints.push_back(j);
  for (int k = j + 1; k < skeleton.subtree_end(j); ++k) {
    if (skeleton.parent(k) != j) continue;
    bool leg = false;
    for (const char* thigh : {"left_thigh", "right_thigh"}) {
      const int t = roles.Find(thigh);
      leg = leg || (t >= k && t < skeleton.subtree_end(k));
    }
    if (!leg) joints.push_back(k);
  }
  return joints;
}

}  // namespace

std::vector<std::string> MissingSegments(const Skeleton& skeleton, const MarkerSet& markers,
                                         const MarkerSet& template_markers) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &fk);
  const HumanoidRoles roles = FindHumanoidRoles(skeleton, fk.world_positions);
  if (!roles.humanoid) return {};
  std::vector<std::string> missing;
  for (const char* role : {"pelvis", "left_thigh", "left_shin", "left_foot", "right_thigh", "right_shin",
                           "right_foot"}) {
    if (roles.Find(role) < 0) continue;
    const std::vector<int> joints = SegmentJoints(skeleton, roles, role);
    const auto on = [&](const MarkerSet& set, int m) {
      for (const MarkerAttachment& a : set.marker(m).attachments) {
        if (std::find(joints.begin(), joints.end(), a.joint) != joints.end()) return true;
      }
      return false;
    };
    bool observed = false;
    for (int m = 0; m < markers.num_markers(); ++m) observed = observed || on(markers, m);
    if (observed) continue;
    std::string labels;
    for (int m = 0; m < template_markers.num_markers(); ++m) {
      if (on(template_markers, m)) labels += (labels.empty() ? "" : ", ") + template_markers.label(m);
    }
    missing.push_back(std::string(role) + " (" + skeleton.name(roles.Find(role)) +
                      (labels.empty() ? ")" : "; the template puts " + labels + " there)"));
  }
  return missing;
}

}  // namespace mocapsolve
