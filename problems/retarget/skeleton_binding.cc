#include "problems/retarget/skeleton_binding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <Eigen/SVD>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/retarget/mesh_mapping.h"
#include "problems/retarget/pelvis_rest_correction.h"

namespace mocapsolve {
namespace {

// The error for too few mapped joints, listing (up to 12 of) the target's unmapped joints.
Status TooFewMappedJointsError(const Skeleton& target, const JointMap& map) {
  std::string missing;
  int listed = 0;
  for (int t = 0; t < target.num_joints() && listed < 12; ++t) {
    if (map.source_of_target[t] >= 0) continue;
    missing += (listed++ ? ", " : "") + target.name(t);
  }
  return Status::Error("cannot align the skeletons: " + std::to_string(map.num_mapped()) +
                       " joints map (names, structure) (need " + std::to_string(kMinMappedJoints) +
                       "); target joints without a source joint: " + missing + (listed == 12 ? ", ..." : "") +
                       " (give a joint map)");
}

// q_b: the target's bind-pose joint positions in its world.
Vector3dVector TargetBindPositions(const Skeleton& target, const Pose& target_bind_pose,
                                   const Eigen::Matrix3d& target_world_from_bind) {
  const int nt = target.num_joints();
  FkData target_fk(target);
  ForwardKinematics(target, target_bind_pose, &target_fk);
  Vector3dVector q(nt);
  for (int t = 0; t < nt; ++t) q[t] = target_world_from_bind * target_fk.world_positions[t];
  return q;
}

// U (header, step 2): the rotation taking the source's up axis to +Y. d_t is the vector
// from the lowest to the highest mapped joint of the target's bind pose `q` (Y up), d_s the
// mean, over (up to 100) frames of the motion, of the same vector on the source. The up
// axis is the signed coordinate axis a of the source whose turn to +Y gives d_s the
// elevation of d_t: the one minimizing |asin(a . d_s / |d_s|) - asin(d_t.y / |d_t|)| (the
// heading is free, so this is the best angle between the turned d_s and d_t). For an
// upright humanoid (d_t vertical) that is the axis nearest to d_s; for a quadruped, whose
// head is ahead of and above its feet, it is not. +y is kept unless another axis is better
// by more than 0.1 rad. A source not +y up is noted.
Eigen::Matrix3d SourceUpRotation(const Skeleton& source, const Motion& source_motion, const JointMap& map,
                                 const Vector3dVector& q, std::vector<std::string>* notes) {
  const int nt = static_cast<int>(q.size());
  int low = -1, high = -1;
  for (int t = 0; t < nt; ++t) {
    if (map.source_of_target[t] < 0) continue;
    if (low < 0 || q[t].y() < q[low].y()) low = t;
    if (high < 0 || q[t].y() > q[high].y()) high = t;
  }
  const int s_low = map.source_of_target[low], s_high = map.source_of_target[high];
  FkData fk(source);
  Eigen::Vector3d up_sum = Eigen::Vector3d::Zero();
  const int nf = source_motion.num_frames();
  const int stride = std::max(1, nf / 100);
  for (int f = 0; f < std::max(nf, 1); f += stride) {
    ForwardKinematics(source, nf > 0 ? source_motion.frames[f] : RestPose(source), &fk);
    up_sum += fk.world_positions[s_high] - fk.world_positions[s_low];
  }
  const Eigen::Vector3d target_d = q[high] - q[low];
  const double target_elevation =
      target_d.norm() > 0.0 ? std::asin(std::clamp(target_d.y() / target_d.norm(), -1.0, 1.0)) : M_PI / 2;
  const Eigen::Vector3d d = up_sum.norm() > 0.0 ? Eigen::Vector3d(up_sum.normalized()) : Eigen::Vector3d::UnitY();
  auto miss = [&](int axis, double sign) {
    return std::abs(std::asin(std::clamp(sign * d[axis], -1.0, 1.0)) - target_elevation);
  };
  int axis = 1;
  double sign = 1.0, best = miss(1, 1.0) - 0.1;
  for (int a = 0; a < 3; ++a) {
    for (double s : {1.0, -1.0}) {
      if (miss(a, s) < best) axis = a, sign = s, best = miss(a, s);
    }
  }
  Eigen::Vector3d up_axis = Eigen::Vector3d::Zero();
  up_axis[axis] = sign;
  if (axis != 1 || up_axis[axis] < 0) {
    notes->push_back(std::string("source up axis: ") + (up_axis[axis] < 0 ? "-" : "+") + "xyz"[axis] +
                     " (turned to +y)");
  }
  return Eigen::Quaterniond::FromTwoVectors(up_axis, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

// children[j]: the mapped source joints whose nearest mapped proper ancestor is j (the
// bones the alignment and its angles are about).
std::vector<std::vector<int>> MappedChildren(const Skeleton& source, const JointMap& map) {
  const int ns = source.num_joints();
  std::vector<int> mapped_parent(ns, -1);  // Nearest mapped proper ancestor.
  std::vector<std::vector<int>> children(ns);
  for (int j = 1; j < ns; ++j) {
    const int p = source.parent(j);
    mapped_parent[j] = map.target_of_source[p] >= 0 ? p : mapped_parent[p];
    if (map.target_of_source[j] >= 0 && mapped_parent[j] >= 0) children[mapped_parent[j]].push_back(j);
  }
  return children;
}

// A source pose aligned to the target's bind pose, its world rotations and how far its
// mapped bones are off the target's.
struct Alignment {
  Pose pose;
  std::vector<Eigen::Quaterniond> world;
  double mean_angle = 0.0, max_angle = 0.0;
  std::string worst;
  PelvisCorrection pelvis;  // The root-most mapped joint's correction (pelvis_rest_correction.h).
  std::vector<Eigen::Quaterniond> upright_world;  // C U times the start pose's world rotations.
  Vector3dVector upright_positions;               // C U times its joint positions.
  double stand_deg = 0.0;                         // S's angle: how far the start pose is from standing.
};

// S (header, step 3): the minimal rotation taking the start pose's body axis, from the
// centroid of the mapped joints to the highest mapped joint of the target's bind pose (the
// head), stood up by U, to the target's bind pose's: a start pose that does not stand
// (a rest pose lying down while the motion's root stands it up) is stood up by the whole
// body, not by where its pelvis's children start.
Eigen::Quaterniond StandUp(const JointMap& map, const Vector3dVector& positions, const Vector3dVector& q,
                           const Eigen::Matrix3d& up) {
  Eigen::Vector3d s_mean = Eigen::Vector3d::Zero(), t_mean = Eigen::Vector3d::Zero();
  int count = 0, high = -1;
  for (int t = 0; t < static_cast<int>(q.size()); ++t) {
    const int j = map.source_of_target[t];
    if (j < 0) continue;
    s_mean += positions[j];
    t_mean += q[t];
    ++count;
    if (high < 0 || q[t].y() > q[high].y()) high = t;
  }
  if (count < 2) return Eigen::Quaterniond::Identity();
  const Eigen::Vector3d d_s = up * (positions[map.source_of_target[high]] - s_mean / count);
  const Eigen::Vector3d d_t = q[high] - t_mean / count;
  if (d_s.norm() <= 0.0 || d_t.norm() <= 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond::FromTwoVectors(d_s, d_t);
}

// Rest-pose alignment (header, step 3) from the source pose `start`: per mapped joint, in
// preorder, the rotation (Kabsch) turning its bones to the target's bind-pose bones `q`;
// then the aligned pose's mean and worst bone angles.
void AlignFrom(const Skeleton& source, const Skeleton& target, const JointMap& map, const Vector3dVector& q,
               const std::vector<std::vector<int>>& children, const Eigen::Matrix3d& up, const Pose& start,
               Alignment* result) {
  const int ns = source.num_joints();
  FkData fk(source);
  ForwardKinematics(source, start, &fk);
  const Eigen::Quaterniond stand_up = StandUp(map, fk.world_positions, q, up);
  result->stand_deg = RadToDeg(Eigen::AngleAxisd(stand_up).angle());
  const Eigen::Quaterniond stand = stand_up * Eigen::Quaterniond(up);
  std::vector<Eigen::Quaterniond> correction(ns);
  std::vector<char> below_mapped(ns, 0);  // A mapped proper ancestor.
  int pelvis = -1;                        // The root-most mapped joint with mapped children.
  for (int j = 0; j < ns; ++j) {
    const int p = source.parent(j);
    const Eigen::Quaterniond parent = p < 0 ? stand : correction[p];
    correction[j] = parent;
    below_mapped[j] = p >= 0 && (below_mapped[p] || map.target_of_source[p] >= 0);
    const int t = map.target_of_source[j];
    if (t < 0) continue;
    std::vector<Eigen::Vector3d> u, v;
    for (int c : children[j]) {
      const Eigen::Vector3d a = parent * (fk.world_positions[c] - fk.world_positions[j]);
      const Eigen::Vector3d b = q[map.target_of_source[c]] - q[t];
      if (a.norm() < 1e-9 || b.norm() < 1e-9) continue;
      u.push_back(a.normalized());
      v.push_back(b.normalized());
    }
    if (u.empty()) continue;
    if (below_mapped[j]) {
      correction[j] = (BestRestRotation(u, v) * parent).normalized();
    } else {
      pelvis = j;
      result->pelvis = PelvisRestCorrection(u, v);
      correction[j] = (result->pelvis.rotation * parent).normalized();
    }
  }
  result->pose = start;
  result->upright_world.resize(ns);
  result->upright_positions.resize(ns);
  const Eigen::Quaterniond upright = (result->pelvis.rotation * stand).normalized();
  for (int j = 0; j < ns; ++j) {
    result->upright_world[j] = (upright * fk.world_rotations[j]).normalized();
    result->upright_positions[j] = upright * fk.world_positions[j];
  }
  result->world.resize(ns);
  for (int j = 0; j < ns; ++j) {
    result->world[j] = correction[j] * fk.world_rotations[j];
    const int p = source.parent(j);
    const Eigen::Quaterniond above =
        (p < 0 ? Eigen::Quaterniond::Identity() : result->world[p]) * source.rest_rotation(j);
    result->pose.rotations[j] = (above.conjugate() * result->world[j]).normalized();
  }
  ForwardKinematics(source, result->pose, &fk);
  int bones = 0;
  for (int j = 0; j < ns; ++j) {
    // The pelvis's own bones are left off where its tilt is not (fully) kept: where they
    // start is each rig's design, which the alignment no longer matches.
    if (j == pelvis && result->pelvis.tilt_kept < 1.0) continue;
    for (int c : children[j]) {
      const Eigen::Vector3d a = fk.world_positions[c] - fk.world_positions[j];
      const Eigen::Vector3d b = q[map.target_of_source[c]] - q[map.target_of_source[j]];
      if (a.norm() < 1e-9 || b.norm() < 1e-9) continue;
      const double angle = RadToDeg(std::atan2(a.cross(b).norm(), a.dot(b)));
      result->mean_angle += angle;
      ++bones;
      if (angle > result->max_angle) {
        result->max_angle = angle;
        result->worst = target.name(map.target_of_source[c]);
      }
    }
  }
  if (bones > 0) result->mean_angle /= bones;
}

// The alignment from the source's rest pose or, when that leaves a mapped bone more than
// kRetryAngleDeg off (a rest pose with every bone along one axis, as the CMU FBX files
// have) or does not stand (its body axis more than kStandDeg from the target's: CesiumMan's
// node rest pose lies bent in a plane, its posture all in the animation), from frames of
// the motion; the start with the lowest mean angle among those that stand wins (noted).
Alignment BestAlignment(const Skeleton& source, const Motion& source_motion, const Skeleton& target,
                        const JointMap& map, const Vector3dVector& q, const Eigen::Matrix3d& up,
                        std::vector<std::string>* notes) {
  constexpr double kRetryAngleDeg = 45.0, kStandDeg = 30.0;
  auto better = [&](const Alignment& a, const Alignment& b) {  // Standing first, then the mean angle.
    if ((a.stand_deg > kStandDeg) != (b.stand_deg > kStandDeg)) return b.stand_deg > kStandDeg;
    return a.mean_angle < b.mean_angle;
  };
  const std::vector<std::vector<int>> children = MappedChildren(source, map);
  const int nf = source_motion.num_frames();
  Alignment best;
  AlignFrom(source, target, map, q, children, up, RestPose(source), &best);
  if ((best.max_angle > kRetryAngleDeg || best.stand_deg > kStandDeg) && nf > 0) {
    const double rest_angle = best.max_angle, rest_stand = best.stand_deg;
    int chosen = -1;
    for (int k = 0; k < 8; ++k) {
      const int f = k * nf / 8;
      Alignment candidate;
      AlignFrom(source, target, map, q, children, up, source_motion.frames[f], &candidate);
      if (better(candidate, best)) {
        best = std::move(candidate);
        chosen = f;
      }
    }
    if (chosen >= 0) {
      char note[200];
      std::snprintf(note, sizeof note,
                    "the source's rest pose aligns badly (a bone %.0f deg off, its body %.0f deg from standing); "
                    "aligned from frame %d instead",
                    rest_angle, rest_stand, chosen);
      notes->push_back(note);
    }
  }
  return best;
}

// The vertical extents of the mapped joints: source (aligned pose `positions`) and target
// (bind pose `q`).
void MappedHeightRange(const JointMap& map, const Vector3dVector& positions, const Vector3dVector& q,
                       double* s_min, double* s_max, double* t_min, double* t_max) {
  const int ns = static_cast<int>(positions.size());
  *s_min = *t_min = 1e300;
  *s_max = *t_max = -1e300;
  for (int j = 0; j < ns; ++j) {
    const int t = map.target_of_source[j];
    if (t < 0) continue;
    *s_min = std::min(*s_min, positions[j].y());
    *s_max = std::max(*s_max, positions[j].y());
    *t_min = std::min(*t_min, q[t].y());
    *t_max = std::max(*t_max, q[t].y());
  }
}

// a(t): the target joint whose mapping carries target joint t: t when mapped, else its
// nearest mapped ancestor, else the first mapped joint.
std::vector<int> TargetAnchors(const Skeleton& target, const JointMap& map) {
  const int nt = target.num_joints();
  std::vector<int> anchor(nt, -1);
  int first_mapped = -1;
  for (int t = 0; t < nt; ++t) {
    if (map.source_of_target[t] >= 0) {
      anchor[t] = t;
      if (first_mapped < 0) first_mapped = t;
    } else if (target.parent(t) >= 0) {
      anchor[t] = anchor[target.parent(t)];
    }
  }
  for (int t = 0; t < nt; ++t) {
    if (anchor[t] < 0) anchor[t] = first_mapped;
  }
  return anchor;
}

// Binding (header, step 5): the target mesh's vertices snapped onto the source's bones
// (aligned pose `positions`), per influence, and its influences moved to the source joints.
// The spec's joint_from_bind is left to the caller.
SkinnedMeshSpec SnapTargetMesh(const SkinnedMesh& target_mesh, const Eigen::Matrix3d& target_world_from_bind,
                               const JointMap& map, const std::vector<int>& anchor, const Vector3dVector& positions,
                               const Vector3dVector& q, double scale) {
  SkinnedMeshSpec spec;
  const int nv = target_mesh.num_vertices();
  spec.rest_positions.resize(3, nv);
  spec.rest_normals.resize(3, target_mesh.has_normals() ? nv : 0);
  spec.influences.resize(nv);
  for (int v = 0; v < nv; ++v) {
    const Eigen::Vector3d x = target_world_from_bind * target_mesh.rest_positions().col(v);
    Eigen::Vector3d snapped = Eigen::Vector3d::Zero();
    std::map<int, double> weights;
    double total = 0.0;
    for (int k = target_mesh.weight_begin(v); k < target_mesh.weight_end(v); ++k) {
      const int a = anchor[target_mesh.weight_joint(k)];
      const int s = map.source_of_target[a];
      const double w = target_mesh.weight(k);
      snapped += w * (positions[s] + (x - q[a]) / scale);
      weights[s] += w;
      total += w;
    }
    spec.rest_positions.col(v) = total > 0 ? Eigen::Vector3d(snapped / total) : x / scale;
    if (target_mesh.has_normals()) {
      spec.rest_normals.col(v) = target_world_from_bind * target_mesh.rest_normals().col(v);
    }
    for (const auto& [joint, weight] : weights) spec.influences[v].push_back({joint, weight});
  }
  return spec;
}

// Placement (header, step 6): the shift putting the bound mesh's rest frame origin o_s
// (of `bound_positions`) at o_t / k_m.
Eigen::Vector3d PlacementShift(const SkinnedMesh& target_mesh, const Eigen::Matrix3d& target_world_from_bind,
                               const Eigen::Matrix3Xd& bound_positions) {
  const int nv = target_mesh.num_vertices();
  Eigen::Matrix3Xd target_world(3, nv);
  for (int v = 0; v < nv; ++v) target_world.col(v) = target_world_from_bind * target_mesh.rest_positions().col(v);
  const CharacterFrame target_frame = ComputeCharacterFrame(target_world);
  const CharacterFrame bound_frame = ComputeCharacterFrame(bound_positions);
  return target_frame.origin * (bound_frame.height / target_frame.height) - bound_frame.origin;
}

// joint_from_bind_j = (D_j R^rest_j, P_j)^-1: the (placed) aligned pose is the bind pose.
std::vector<Eigen::Isometry3d> JointFromBind(const Skeleton& source, const Pose& aligned) {
  const int ns = source.num_joints();
  FkData fk(source);
  ForwardKinematics(source, aligned, &fk);
  std::vector<Eigen::Isometry3d> joint_from_bind(ns);
  for (int j = 0; j < ns; ++j) {
    Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
    world_from_joint.linear() = fk.world_rotations[j].toRotationMatrix();
    world_from_joint.translation() = fk.world_positions[j];
    joint_from_bind[j] = world_from_joint.inverse();
  }
  return joint_from_bind;
}

}  // namespace

Motion RotateMotionWorld(const Skeleton& skeleton, const Motion& motion, const Eigen::Matrix3d& rotation) {
  Motion out = motion;
  RotateMotionWorld(skeleton, rotation, &out);
  return out;
}

void RotateMotionWorld(const Skeleton& skeleton, const Eigen::Matrix3d& rotation, Motion* motion) {
  const Eigen::Quaterniond u(rotation);
  const Eigen::Quaterniond rest = skeleton.rest_rotation(0);
  for (Pose& pose : motion->frames) {
    pose.translations[0] = rotation * pose.translations[0];
    pose.rotations[0] = (rest.conjugate() * u * rest * pose.rotations[0]).normalized();
  }
}

Status BindTargetMeshToSource(const Skeleton& source, const Motion& source_motion, const Skeleton& target,
                              const SkinnedMesh& target_mesh, const Pose& target_bind_pose,
                              const Eigen::Matrix3d& target_world_from_bind, const JointMap& map,
                              SkeletonBinding* binding) {
  if (map.num_mapped() < kMinMappedJoints) return TooFewMappedJointsError(target, map);
  SkeletonBinding out;
  const Vector3dVector q = TargetBindPositions(target, target_bind_pose, target_world_from_bind);
  out.up = SourceUpRotation(source, source_motion, map, q, &out.notes);

  Alignment best = BestAlignment(source, source_motion, target, map, q, out.up, &out.notes);
  Pose aligned = std::move(best.pose);
  out.mean_bone_angle_deg = best.mean_angle;
  out.max_bone_angle_deg = best.max_angle;
  out.worst_bone = best.worst;
  out.pelvis_residual_deg = best.pelvis.residual_deg;
  out.pelvis_tilt_kept = best.pelvis.tilt_kept;
  out.upright_world = std::move(best.upright_world);
  out.upright_positions = std::move(best.upright_positions);
  FkData fk(source);
  ForwardKinematics(source, aligned, &fk);

  // Scale from the vertical extents of the mapped joints.
  double s_min, s_max, t_min, t_max;
  MappedHeightRange(map, fk.world_positions, q, &s_min, &s_max, &t_min, &t_max);
  if (!(s_max - s_min > 0.0) || !(t_max - t_min > 0.0)) {
    return Status::Error("cannot align the skeletons: the mapped joints have no vertical extent");
  }
  out.source_height = s_max - s_min;
  out.scale = (t_max - t_min) / out.source_height;

  // The target mesh on the source skeleton, placed (see the header).
  SkinnedMeshSpec spec = SnapTargetMesh(target_mesh, target_world_from_bind, map, TargetAnchors(target, map),
                                        fk.world_positions, q, out.scale);
  const Eigen::Vector3d shift = PlacementShift(target_mesh, target_world_from_bind, spec.rest_positions);
  spec.rest_positions.colwise() += shift;
  aligned.translations[0] += shift;
  spec.joint_from_bind = JointFromBind(source, aligned);
  Status status = SkinnedMesh::Create(source, std::move(spec), &out.mesh);
  if (!status.ok()) return Status::Error("binding the target mesh to the source skeleton: " + status.message());
  out.aligned_pose = std::move(aligned);
  *binding = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
