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

// The limbs of the map, each with no directions yet.
std::vector<LimbDirections> LimbsToCollect(const JointMap& map, std::vector<MappedLimb>* mapped) {
  *mapped = MappedLimbs(map);
  std::vector<LimbDirections> limbs(mapped->size());
  for (size_t i = 0; i < mapped->size(); ++i) limbs[i].limb = (*mapped)[i].limb;
  return limbs;
}

// One frame's limb directions appended (frames in order: each limb's series is the clip's).
void CollectLimbDirections(const std::vector<MappedLimb>& mapped, const Vector3dVector& source_positions,
                           const Vector3dVector& target_positions, std::vector<LimbDirections>* limbs) {
  for (size_t i = 0; i < mapped.size(); ++i) {
    const MappedLimb& m = mapped[i];
    const Eigen::Vector3d s = source_positions[m.source_to] - source_positions[m.source_from];
    const Eigen::Vector3d t = target_positions[m.target_to] - target_positions[m.target_from];
    if (s.norm() <= 0.0 || t.norm() <= 0.0) continue;  // A zero-length bone has no direction.
    (*limbs)[i].source.push_back(s.normalized());
    (*limbs)[i].target.push_back(t.normalized());
  }
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

// The pelvis's orientation and the chest's lean (header), tallied frame by frame.
class TorsoOrientationTally {
 public:
  explicit TorsoOrientationTally(const RetargetQualityInputs& in) {
    if (in.source_upright == nullptr || in.source_upright_positions == nullptr) return;
    const JointMap& map = *in.joint_map;
    const int ns = static_cast<int>(in.source_upright->size());
    auto source_of = [&](int t, const char* role) { return t < 0 ? -1 : SourceJoint(map, role, t); };
    pelvis_t_ = TargetJoint(map, "pelvis");
    pelvis_s_ = source_of(pelvis_t_, "pelvis");
    chest_t_ = TargetJoint(map, "chest");
    neck_t_ = TargetJoint(map, "neck");
    chest_s_ = source_of(chest_t_, "chest");
    neck_s_ = source_of(neck_t_, "neck");
    FkData fk(*in.target);
    ForwardKinematics(*in.target, in.target_bind.rotations.empty() ? RestPose(*in.target) : in.target_bind, &fk);
    const Vector3dVector& upright = *in.source_upright_positions;
    auto zero_length = [&](int s, int t) {
      return s < 0 || t < 0 || s >= ns || (upright[neck_s_] - upright[s]).norm() <= 0.0 ||
             (fk.world_positions[neck_t_] - fk.world_positions[t]).norm() <= 0.0;
    };
    if (neck_s_ >= 0 && neck_s_ < ns && zero_length(chest_s_, chest_t_)) {  // CMU's BVH: Chest2 at lowerneck.
      chest_t_ = TargetJoint(map, "spine_1");
      chest_s_ = source_of(chest_t_, "spine_1");
    }
    const Eigen::Quaterniond world_from_bind(in.target_world_from_bind);
    if (pelvis_s_ < 0 || pelvis_s_ >= ns) {
      pelvis_s_ = -1;
    } else {
      pelvis_target_reference_ = world_from_bind * fk.world_rotations[pelvis_t_];
      pelvis_source_reference_ = (*in.source_upright)[pelvis_s_];
    }
    if (chest_s_ < 0 || neck_s_ < 0 || chest_s_ >= ns || neck_s_ >= ns) {
      chest_s_ = -1;
      return;
    }
    const Eigen::Vector3d d0_s = (*in.source_upright_positions)[neck_s_] - (*in.source_upright_positions)[chest_s_];
    const Eigen::Vector3d d0_t =
        in.target_world_from_bind * (fk.world_positions[neck_t_] - fk.world_positions[chest_t_]);
    if (d0_s.norm() <= 0.0 || d0_t.norm() <= 0.0) {
      chest_s_ = -1;
      return;
    }
    design_ = Eigen::Quaterniond::FromTwoVectors(d0_s, d0_t);
  }
  void Add(const FkData& source_fk, const FkData& target_fk) {
    if (pelvis_s_ >= 0) {
      const Eigen::Quaterniond d_s = source_fk.world_rotations[pelvis_s_] * pelvis_source_reference_.conjugate();
      const Eigen::Quaterniond d_t = target_fk.world_rotations[pelvis_t_] * pelvis_target_reference_.conjugate();
      pelvis_.push_back(Eigen::AngleAxisd((d_s.conjugate() * d_t).normalized()).angle() * kDegreesPerRadian);
    }
    if (chest_s_ >= 0) {
      const Eigen::Vector3d a =
          design_ * (source_fk.world_positions[neck_s_] - source_fk.world_positions[chest_s_]);
      const Eigen::Vector3d b = target_fk.world_positions[neck_t_] - target_fk.world_positions[chest_t_];
      if (a.norm() > 0.0 && b.norm() > 0.0) {
        chest_.push_back(std::atan2(a.cross(b).norm(), a.dot(b)) * kDegreesPerRadian);
      }
    }
  }
  void Result(RetargetQuality* quality) const {
    quality->pelvis_orientation_mean_deg = Mean(pelvis_);
    quality->pelvis_orientation_p95_deg = Percentile95(pelvis_);
    quality->chest_orientation_mean_deg = Mean(chest_);
    quality->chest_orientation_p95_deg = Percentile95(chest_);
  }

 private:
  int pelvis_s_ = -1, pelvis_t_ = -1, chest_s_ = -1, chest_t_ = -1, neck_s_ = -1, neck_t_ = -1;
  Eigen::Quaterniond pelvis_source_reference_, pelvis_target_reference_, design_;
  std::vector<double> pelvis_, chest_;
};

// Depth of each joint of `feet` under its rest clearance above y = 0 (foot_clearance.h) per
// frame, times `scale`: the deepest and the share of frames deeper than share_depth,
// tallied frame by frame.
class PenetrationTally {
 public:
  PenetrationTally(const Skeleton& skeleton, const std::vector<int>& feet, const Pose& rest, const SkinnedMesh* mesh,
                   double scale, double share_depth)
      : feet_(feet), scale_(scale), share_depth_(share_depth) {
    if (!feet.empty()) clearances_ = FootRestClearances(skeleton, feet, rest, mesh);
  }
  void Add(const Vector3dVector& frame) {
    ++frames_;
    if (feet_.empty()) return;
    double frame_depth = 0.0;
    for (size_t k = 0; k < feet_.size(); ++k) {
      frame_depth = std::max(frame_depth, (clearances_[k] - frame[feet_[k]].y()) * scale_);
    }
    deepest_ = std::max(deepest_, frame_depth);
    over_ += frame_depth > share_depth_ ? 1 : 0;
  }
  void Result(double* deepest, double* share_over) const {
    *deepest = 0.0;
    *share_over = 0.0;
    if (feet_.empty() || frames_ == 0) return;
    *deepest = deepest_;
    *share_over = double(over_) / frames_;
  }

 private:
  std::vector<int> feet_;
  double scale_, share_depth_;
  std::vector<double> clearances_;
  double deepest_ = 0.0;
  int over_ = 0;
  long frames_ = 0;
};

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

// The own skeleton's joint error, tallied frame by frame (frames, then joints, in order).
class SelfJointTally {
 public:
  SelfJointTally(const RetargetQualityInputs& in, double cm) : in_(in), cm_(cm) {}
  void Add(const Vector3dVector& source_positions, const Vector3dVector& target_positions) {
    if (!in_.own_skeleton) return;
    for (int j = 0; j < in_.source->num_joints(); ++j) {
      const int t = in_.joint_map->target_of_source[j];
      if (t < 0) continue;
      const double e = (in_.own_scale * source_positions[j] - target_positions[t]).norm() * cm_;
      sum_ += e;
      max_ = std::max(max_, e);
      ++count_;
    }
  }
  void Result(RetargetQuality* quality) const {
    quality->self_joint_error_mean_cm = quality->self_joint_error_max_cm = std::nan("");
    if (!in_.own_skeleton || count_ == 0) return;
    quality->self_joint_error_mean_cm = sum_ / count_;
    quality->self_joint_error_max_cm = max_;
  }

 private:
  const RetargetQualityInputs& in_;
  double cm_;
  double sum_ = 0.0, max_ = 0.0;
  int count_ = 0;
};

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
  const Pose target_rest = in.target_rest.rotations.empty() ? RestPose(*in.target) : in.target_rest;
  std::vector<MappedLimb> mapped;
  std::vector<LimbDirections> limbs = LimbsToCollect(*in.joint_map, &mapped);
  PenetrationTally penetration(*in.target, TargetFootJoints(*in.joint_map), target_rest, in.target_mesh, cm, 1.0);
  SelfJointTally self(in, cm);
  TorsoOrientationTally torso(in);
  // One pass over the frames, both skeletons' joints of one frame at a time (the clip's
  // would be 2.4 KB per frame of a long take onto Xbot).
  const int frames = std::min(in.source_motion->num_frames(), in.result->num_frames());
  FkData source_fk(*in.source), target_fk(*in.target);
  for (int f = 0; f < in.result->num_frames(); ++f) {
    ForwardKinematics(*in.target, in.result->frames[f], &target_fk);
    penetration.Add(target_fk.world_positions);
    if (f >= frames) continue;
    ForwardKinematics(*in.source, in.source_motion->frames[f], &source_fk);
    CollectLimbDirections(mapped, source_fk.world_positions, target_fk.world_positions, &limbs);
    self.Add(source_fk.world_positions, target_fk.world_positions);
    torso.Add(source_fk, target_fk);
  }
  torso.Result(&quality);
  MeasureLimbDirections(limbs, &quality);
  quality.foot_skate_cm_s = in.foot_skate_cm_s;
  penetration.Result(&quality.penetration_cm, &quality.penetration_frame_share);
  self.Result(&quality);
  if (in.setup != nullptr && in.target_mesh != nullptr) {
    MeasureCoverage(*in.target, *in.target_mesh, *in.joint_map, *in.setup, &quality);
  }
  return quality;
}

}  // namespace mocapsolve
