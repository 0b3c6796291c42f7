#include "kinematics/skeleton.h"

#include <cmath>
#include <set>
#include <vector>

#include "kinematics/quote_token.h"

namespace mocapsolve {

Status Skeleton::Create(std::vector<JointSpec> joints, std::vector<EndSite> end_sites,
                        LengthUnit unit, Skeleton* skeleton) {
  if (joints.empty()) return Status::Error("skeleton has no joints");
  std::set<std::string> names;
  std::vector<int> depth(joints.size(), 0);
  for (int j = 0; j < static_cast<int>(joints.size()); ++j) {
    const JointSpec& spec = joints[j];
    const std::string where = "joint " + std::to_string(j) + " " + QuoteToken(spec.name);
    if (spec.name.empty()) return Status::Error(where + ": empty name");
    if (!names.insert(spec.name).second) return Status::Error(where + ": duplicate name");
    if (j == 0 && spec.parent != -1) return Status::Error(where + ": the root has a parent");
    if (j > 0 && (spec.parent < 0 || spec.parent >= j)) {
      return Status::Error(where + ": parent index " + std::to_string(spec.parent) +
                           " is not an earlier joint (joints must be in preorder)");
    }
    if (j > 0 && (depth[j] = depth[spec.parent] + 1) > kMaxSkeletonDepth) {
      return Status::Error(where + ": nested deeper than " + std::to_string(kMaxSkeletonDepth) +
                           " joints below the root");
    }
    if (!spec.offset.allFinite()) return Status::Error(where + ": offset is not finite");
    if (!spec.rest_rotation.coeffs().allFinite() ||
        std::abs(spec.rest_rotation.norm() - 1.0) > 1e-9) {
      return Status::Error(where + ": rest rotation is not a unit quaternion");
    }
    std::set<Channel> seen;
    for (Channel c : spec.channels) {
      if (!seen.insert(c).second) return Status::Error(where + ": repeated channel");
    }
    if (!spec.rotation_limits.empty()) {
      const size_t dofs = spec.rotation_axes.has_value() ? spec.rotation_axes->size() : 3;
      if (spec.rotation_limits.size() != dofs) {
        return Status::Error(where + ": one limit pair per rotation dof expected");
      }
      for (const auto& [lower, upper] : spec.rotation_limits) {
        if (std::isnan(lower) || std::isnan(upper) || lower > upper) {
          return Status::Error(where + ": bad rotation limits");
        }
      }
    }
    std::set<int> axes;
    for (int axis : spec.rotation_axes.value_or(std::vector<int>())) {
      if (axis < 0 || axis > 2 || !axes.insert(axis).second) {
        return Status::Error(where + ": bad or repeated rotation axis");
      }
    }
  }
  for (const EndSite& site : end_sites) {
    if (site.parent < 0 || site.parent >= static_cast<int>(joints.size()) ||
        !site.offset.allFinite()) {
      return Status::Error("end site " + QuoteToken(site.name) + ": bad parent or offset");
    }
  }

  Skeleton s;
  const int n = static_cast<int>(joints.size());
  s.subtree_end_.assign(n, 0);
  // In preorder, j's subtree ends where the next joint whose parent precedes j begins.
  for (int j = n - 1; j >= 0; --j) {
    int end = j + 1;
    while (end < n && joints[end].parent >= j) {
      end = s.subtree_end_[end];
    }
    s.subtree_end_[j] = end;
  }
  s.has_rest_rotation_.resize(n);
  s.has_translation_channels_.resize(n);
  s.rotation_axes_.resize(n);
  for (int j = 0; j < n; ++j) {
    s.has_rest_rotation_[j] = !joints[j].rest_rotation.isApprox(Eigen::Quaterniond::Identity(), 0.0);
    bool translation = false;
    for (Channel c : joints[j].channels) {
      translation |= c == Channel::kXposition || c == Channel::kYposition ||
                     c == Channel::kZposition;
    }
    s.has_translation_channels_[j] = translation;
    std::vector<int>& axes = s.rotation_axes_[j];
    if (joints[j].rotation_axes.has_value()) {
      axes = *joints[j].rotation_axes;
    } else if (joints[j].channels.empty()) {
      axes = {0, 1, 2};
    } else {
      for (Channel c : joints[j].channels) {
        if (c == Channel::kXrotation) axes.push_back(0);
        if (c == Channel::kYrotation) axes.push_back(1);
        if (c == Channel::kZrotation) axes.push_back(2);
      }
    }
  }
  s.joints_ = std::move(joints);
  s.end_sites_ = std::move(end_sites);
  s.unit_ = std::move(unit);
  *skeleton = std::move(s);
  return Status::Ok();
}

int Skeleton::FindJoint(const std::string& name) const {
  for (int j = 0; j < num_joints(); ++j) {
    if (joints_[j].name == name) return j;
  }
  return -1;
}

}  // namespace mocapsolve
