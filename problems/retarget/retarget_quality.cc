#include "problems/retarget/retarget_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/SVD>

#include "kinematics/forward_kinematics.h"
#include "kinematics/skinning.h"
#include "problems/retarget/foot_clearance.h"

namespace mocapsolve {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

double Percentile95(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  const size_t k = static_cast<size_t>(std::ceil(0.95 * values.size())) - 1;
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

double Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nan("");
  double sum = 0.0;
  for (double v : values) sum += v;
  return sum / values.size();
}

// R maximizing sum <t_i, R s_i> (Kabsch).
Eigen::Matrix3d BestRotation(const Eigen::Matrix3d& t_s) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(t_s, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

// The target joint of a role: the joint map's (roles linked across, names included), else the
// target's own.
int TargetJoint(const JointMap& map, const std::string& role) {
  for (const JointMapRole& r : map.roles) {
    if (r.role == role && r.target >= 0) return r.target;
  }
  return map.target_roles.Find(role);
}

// The source joint of a role: the one mapped to the target's role joint `t`, else the joint
// map's, else the source's own role.
int SourceJoint(const JointMap& map, const std::string& role, int t) {
  if (t >= 0 && map.source_of_target[t] >= 0) return map.source_of_target[t];
  for (const JointMapRole& r : map.roles) {
    if (r.role == role && r.source >= 0) return r.source;
  }
  return map.source_roles.Find(role);
}

// Per limb: its source and target joints (role, next role) and per frame unit directions.
struct LimbDirections {
  std::string limb;
  std::vector<Eigen::Vector3d> source, target;
};

std::vector<LimbDirections> CollectLimbDirections(const JointMap& map,
                                                  const std::vector<Vector3dVector>& source_positions,
                                                  const std::vector<Vector3dVector>& target_positions) {
  std::vector<LimbDirections> limbs;
  for (const MappedLimb& mapped : MappedLimbs(map)) {
    const int s0 = mapped.source_from, s1 = mapped.source_to, t0 = mapped.target_from, t1 = mapped.target_to;
    LimbDirections limb;
    limb.limb = mapped.limb;
    const size_t frames = std::min(source_positions.size(), target_positions.size());
    for (size_t f = 0; f < frames; ++f) {
      const Eigen::Vector3d s = source_positions[f][s1] - source_positions[f][s0];
      const Eigen::Vector3d t = target_positions[f][t1] - target_positions[f][t0];
      if (s.norm() <= 0.0 || t.norm() <= 0.0) continue;  // A zero-length bone has no direction.
      limb.source.push_back(s.normalized());
      limb.target.push_back(t.normalized());
    }
    limbs.push_back(std::move(limb));
  }
  return limbs;
}

void MeasureLimbDirections(const std::vector<LimbDirections>& limbs, RetargetQuality* quality) {
  Eigen::Matrix3d t_s = Eigen::Matrix3d::Zero();
  for (const LimbDirections& limb : limbs) {
    for (size_t i = 0; i < limb.source.size(); ++i) t_s += limb.target[i] * limb.source[i].transpose();
  }
  const Eigen::Matrix3d rotation = BestRotation(t_s);
  quality->alignment_deg = Eigen::AngleAxisd(rotation).angle() * kDegreesPerRadian;
  std::vector<double> all, means;
  for (const LimbDirections& limb : limbs) {
    std::vector<double> errors;
    for (size_t i = 0; i < limb.source.size(); ++i) {
      const double cosine = std::clamp(limb.target[i].dot(rotation * limb.source[i]), -1.0, 1.0);
      errors.push_back(std::acos(cosine) * kDegreesPerRadian);
    }
    LimbDirectionError e;
    e.limb = limb.limb;
    e.mean_deg = Mean(errors);
    e.p95_deg = Percentile95(errors);
    means.push_back(e.mean_deg);
    all.insert(all.end(), errors.begin(), errors.end());
    quality->limbs.push_back(e);
  }
  quality->limb_mean_deg = Mean(means);
  quality->limb_p95_deg = Percentile95(all);
}

// Depth of each joint of `feet` under its rest clearance above y = 0 (foot_clearance.h) per
// frame, times `scale`.
void MeasurePenetration(const Skeleton& skeleton, const std::vector<int>& feet, const Pose& rest,
                        const SkinnedMesh* mesh, const std::vector<Vector3dVector>& positions, double scale,
                        double* deepest, double* share_over, double share_depth) {
  *deepest = 0.0;
  *share_over = 0.0;
  if (feet.empty() || positions.empty()) return;
  const std::vector<double> clearances = FootRestClearances(skeleton, feet, rest, mesh);
  int over = 0;
  for (const Vector3dVector& frame : positions) {
    double frame_depth = 0.0;
    for (size_t k = 0; k < feet.size(); ++k) {
      frame_depth = std::max(frame_depth, (clearances[k] - frame[feet[k]].y()) * scale);
    }
    *deepest = std::max(*deepest, frame_depth);
    over += frame_depth > share_depth ? 1 : 0;
  }
  *share_over = double(over) / positions.size();
}

// Tracked vertices per body part (the role of the heaviest joint's nearest role ancestor).
void MeasureCoverage(const Skeleton& target, const SkinnedMesh& mesh, const JointMap& map, const RetargetSetup& setup,
                     RetargetQuality* quality) {
  HumanoidRoles roles;  // The target's role joints (TargetJoint), in the template's order.
  for (const auto& [role, joint] : map.target_roles.roles) roles.roles.emplace_back(role, TargetJoint(map, role));
  for (const JointMapRole& r : map.roles) {
    if (r.target >= 0 && roles.Find(r.role) < 0) roles.roles.emplace_back(r.role, r.target);
  }
  const std::vector<int> part = BodyParts(target, roles);  // Index into roles.roles.
  std::vector<int> counts(roles.roles.size() + 1, 0);  // Last: no part.
  for (const TrackedVertex& t : setup.tracked) {
    int heaviest = -1;
    double weight = -1.0;
    for (int k = mesh.weight_begin(t.target_vertex); k < mesh.weight_end(t.target_vertex); ++k) {
      if (mesh.weight(k) > weight) weight = mesh.weight(k), heaviest = mesh.weight_joint(k);
    }
    const int p = heaviest >= 0 ? part[heaviest] : -1;
    ++counts[p >= 0 ? p : roles.roles.size()];
  }
  for (size_t r = 0; r < roles.roles.size(); ++r) quality->coverage.emplace_back(roles.roles[r].first, counts[r]);
  if (counts.back() > 0) quality->coverage.emplace_back("other", counts.back());
  quality->min_limb_vertices = 0;
  bool first = true;
  for (const auto& [from, to] : HumanoidLimbs()) {
    const int r = roles.Find(from) >= 0 ? part[roles.Find(from)] : -1;
    if (r < 0) continue;
    // The limb's direction runs from its joint to the next role's: vertices on its own part
    // or on the part at its end pin it (RobotExpressive's forearms carry no mesh; their
    // hands' vertices place them).
    const int end = roles.Find(to) >= 0 ? part[roles.Find(to)] : -1;
    const int tracked = counts[r] + (end >= 0 && end != r ? counts[end] : 0);
    for (LimbDirectionError& limb : quality->limbs) {
      if (limb.limb == from) limb.tracked_vertices = tracked;
    }
    if (first || tracked < quality->min_limb_vertices) {
      quality->min_limb_vertices = tracked;
      quality->least_covered_limb = from;
      first = false;
    }
  }
}

void MeasureSelfJointError(const RetargetQualityInputs& in, const std::vector<Vector3dVector>& source_positions,
                           const std::vector<Vector3dVector>& target_positions, double cm,
                           RetargetQuality* quality) {
  quality->self_joint_error_mean_cm = quality->self_joint_error_max_cm = std::nan("");
  if (!in.own_skeleton) return;
  double sum = 0.0, max = 0.0;
  int count = 0;
  for (size_t f = 0; f < std::min(source_positions.size(), target_positions.size()); ++f) {
    for (int j = 0; j < in.source->num_joints(); ++j) {
      const int t = in.joint_map->target_of_source[j];
      if (t < 0) continue;
      const double e = (in.own_scale * source_positions[f][j] - target_positions[f][t]).norm() * cm;
      sum += e;
      max = std::max(max, e);
      ++count;
    }
  }
  if (count == 0) return;
  quality->self_joint_error_mean_cm = sum / count;
  quality->self_joint_error_max_cm = max;
}

}  // namespace

std::vector<MappedLimb> MappedLimbs(const JointMap& map) {
  std::vector<MappedLimb> limbs;
  for (const auto& [from, to] : HumanoidLimbs()) {
    MappedLimb limb;
    limb.limb = from;
    limb.target_from = TargetJoint(map, from);
    limb.target_to = TargetJoint(map, to);
    limb.source_from = SourceJoint(map, from, limb.target_from);
    limb.source_to = SourceJoint(map, to, limb.target_to);
    if (limb.source_from < 0 || limb.source_to < 0 || limb.target_from < 0 || limb.target_to < 0) continue;
    limbs.push_back(limb);
  }
  return limbs;
}

std::vector<int> TargetFootJoints(const JointMap& map) {
  std::vector<int> feet;
  for (const char* role : {"left_foot", "right_foot", "left_toes", "right_toes"}) {
    const int j = TargetJoint(map, role);
    if (j >= 0 && std::find(feet.begin(), feet.end(), j) == feet.end()) feet.push_back(j);
  }
  return feet;
}

const std::vector<std::pair<std::string, std::string>>& HumanoidLimbs() {
  static const std::vector<std::pair<std::string, std::string>> limbs = {
      {"left_upper_arm", "left_forearm"}, {"left_forearm", "left_hand"},  {"right_upper_arm", "right_forearm"},
      {"right_forearm", "right_hand"},    {"left_thigh", "left_shin"},    {"left_shin", "left_foot"},
      {"right_thigh", "right_shin"},      {"right_shin", "right_foot"}};
  return limbs;
}

RetargetQuality MeasureRetargetQuality(const RetargetQualityInputs& in) {
  RetargetQuality quality;
  const double cm = in.target->unit().known() ? 100.0 * in.target->unit().metres_per_unit : 1.0;
  const std::vector<Vector3dVector> source_positions = ClipJointPositions(*in.source, *in.source_motion);
  const std::vector<Vector3dVector> target_positions = ClipJointPositions(*in.target, *in.result);
  MeasureLimbDirections(CollectLimbDirections(*in.joint_map, source_positions, target_positions), &quality);
  quality.foot_skate_cm_s = in.foot_skate_cm_s;
  const Pose target_rest = in.target_rest.rotations.empty() ? RestPose(*in.target) : in.target_rest;
  const std::vector<int> target_feet = TargetFootJoints(*in.joint_map);
  MeasurePenetration(*in.target, target_feet, target_rest, in.target_mesh, target_positions, cm,
                     &quality.penetration_cm, &quality.penetration_frame_share, 1.0);
  MeasureSelfJointError(in, source_positions, target_positions, cm, &quality);
  if (in.setup != nullptr && in.target_mesh != nullptr) {
    MeasureCoverage(*in.target, *in.target_mesh, *in.joint_map, *in.setup, &quality);
  }
  return quality;
}

}  // namespace mocapsolve
