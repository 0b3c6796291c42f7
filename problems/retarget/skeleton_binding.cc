#include "problems/retarget/skeleton_binding.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <Eigen/SVD>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "problems/retarget/mesh_mapping.h"

namespace mocapsolve {
namespace {

// argmin_R sum |R u_i - v_i|^2 over unit vectors (Kabsch), or the minimal rotation taking
// the mean u to the mean v when the u are (nearly) parallel: then the rotation about them
// is not determined (CMU's thorax, whose neck and both clavicles start at one point) and
// the minimal one keeps the source's.
Eigen::Quaterniond BestRotation(const std::vector<Eigen::Vector3d>& u, const std::vector<Eigen::Vector3d>& v) {
  Eigen::Vector3d mean_u = Eigen::Vector3d::Zero(), mean_v = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < u.size(); ++i) {
    mean_u += u[i];
    mean_v += v[i];
  }
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < u.size(); ++i) h += u[i] * v[i].transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  if (u.size() == 1 || svd.singularValues()(1) < 0.05 * svd.singularValues()(0)) {
    return Eigen::Quaterniond::FromTwoVectors(mean_u, mean_v);
  }
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return Eigen::Quaterniond(Eigen::Matrix3d(svd.matrixV() * d * svd.matrixU().transpose())).normalized();
}

}  // namespace

Motion RotateMotionWorld(const Skeleton& skeleton, const Motion& motion, const Eigen::Matrix3d& rotation) {
  Motion out = motion;
  const Eigen::Quaterniond u(rotation);
  const Eigen::Quaterniond rest = skeleton.rest_rotation(0);
  for (Pose& pose : out.frames) {
    pose.translations[0] = rotation * pose.translations[0];
    pose.rotations[0] = (rest.conjugate() * u * rest * pose.rotations[0]).normalized();
  }
  return out;
}

Status BindTargetMeshToSource(const Skeleton& source, const Motion& source_motion, const Skeleton& target,
                              const SkinnedMesh& target_mesh, const Pose& target_bind_pose,
                              const Eigen::Matrix3d& target_world_from_bind, const JointMap& map,
                              SkeletonBinding* binding) {
  const int ns = source.num_joints(), nt = target.num_joints();
  if (map.num_mapped() < kMinMappedJoints) {
    std::string missing;
    int listed = 0;
    for (int t = 0; t < nt && listed < 12; ++t) {
      if (map.source_of_target[t] >= 0) continue;
      missing += (listed++ ? ", " : "") + target.name(t);
    }
    return Status::Error("cannot align the skeletons: " + std::to_string(map.num_mapped()) +
                         " joints map (names, structure) (need " + std::to_string(kMinMappedJoints) +
                         "); target joints without a source joint: " + missing +
                         (listed == 12 ? ", ..." : "") + " (give a joint map)");
  }
  SkeletonBinding out;
  // Target bind pose in its world.
  FkData target_fk(target);
  ForwardKinematics(target, target_bind_pose, &target_fk);
  std::vector<Eigen::Vector3d> q(nt);
  for (int t = 0; t < nt; ++t) q[t] = target_world_from_bind * target_fk.world_positions[t];

  // Up axis from the lowest and highest mapped joints of the target's bind pose.
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
  int axis = 0;
  up_sum.cwiseAbs().maxCoeff(&axis);
  Eigen::Vector3d up_axis = Eigen::Vector3d::Zero();
  up_axis[axis] = up_sum[axis] < 0 ? -1.0 : 1.0;
  out.up = Eigen::Quaterniond::FromTwoVectors(up_axis, Eigen::Vector3d::UnitY()).toRotationMatrix();
  if (axis != 1 || up_axis[axis] < 0) {
    out.notes.push_back(std::string("source up axis: ") + (up_axis[axis] < 0 ? "-" : "+") + "xyz"[axis] +
                        " (turned to +y)");
  }

  // Rest-pose alignment, from the source's rest pose or, when that leaves a mapped bone
  // more than kRetryAngleDeg off (a rest pose with every bone along one axis, as the CMU
  // FBX files have), from frames of the motion; the start with the lowest mean angle wins.
  std::vector<int> mapped_parent(ns, -1);  // Nearest mapped proper ancestor.
  std::vector<std::vector<int>> children(ns);
  for (int j = 1; j < ns; ++j) {
    const int p = source.parent(j);
    mapped_parent[j] = map.target_of_source[p] >= 0 ? p : mapped_parent[p];
    if (map.target_of_source[j] >= 0 && mapped_parent[j] >= 0) children[mapped_parent[j]].push_back(j);
  }
  struct Alignment {
    Pose pose;
    std::vector<Eigen::Quaterniond> world;
    double mean_angle = 0.0, max_angle = 0.0;
    std::string worst;
  };
  auto align = [&](const Pose& start, Alignment* result) {
    ForwardKinematics(source, start, &fk);
    std::vector<Eigen::Quaterniond> correction(ns);
    for (int j = 0; j < ns; ++j) {
      const Eigen::Quaterniond parent =
          source.parent(j) < 0 ? Eigen::Quaterniond::Identity() : correction[source.parent(j)];
      correction[j] = parent;
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
      if (!u.empty()) correction[j] = (BestRotation(u, v) * parent).normalized();
    }
    result->pose = start;
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
  };
  constexpr double kRetryAngleDeg = 45.0;
  Alignment best;
  align(RestPose(source), &best);
  if (best.max_angle > kRetryAngleDeg && nf > 0) {
    const double rest_angle = best.max_angle;
    int chosen = -1;
    for (int k = 0; k < 8; ++k) {
      const int f = k * nf / 8;
      Alignment candidate;
      align(source_motion.frames[f], &candidate);
      if (candidate.mean_angle < best.mean_angle) {
        best = std::move(candidate);
        chosen = f;
      }
    }
    if (chosen >= 0) {
      char note[200];
      std::snprintf(note, sizeof note,
                    "the source's rest pose aligns badly (a bone %.0f deg off); aligned from frame %d instead",
                    rest_angle, chosen);
      out.notes.push_back(note);
    }
  }
  Pose aligned = best.pose;
  std::vector<Eigen::Quaterniond>& world = best.world;
  out.mean_bone_angle_deg = best.mean_angle;
  out.max_bone_angle_deg = best.max_angle;
  out.worst_bone = best.worst;
  ForwardKinematics(source, aligned, &fk);
  const Vector3dVector& positions = fk.world_positions;
  const auto map_height = [&](double* s_min, double* s_max, double* t_min, double* t_max) {
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
  };

  // Scale from the vertical extents of the mapped joints.
  double s_min, s_max, t_min, t_max;
  map_height(&s_min, &s_max, &t_min, &t_max);
  if (!(s_max - s_min > 0.0) || !(t_max - t_min > 0.0)) {
    return Status::Error("cannot align the skeletons: the mapped joints have no vertical extent");
  }
  out.source_height = s_max - s_min;
  out.scale = (t_max - t_min) / out.source_height;

  // The target mesh on the source skeleton.
  std::vector<int> anchor(nt, -1);  // Target joint whose mapping carries joint t.
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
      snapped += w * (positions[s] + (x - q[a]) / out.scale);
      weights[s] += w;
      total += w;
    }
    spec.rest_positions.col(v) = total > 0 ? Eigen::Vector3d(snapped / total) : x / out.scale;
    if (target_mesh.has_normals()) spec.rest_normals.col(v) = target_world_from_bind * target_mesh.rest_normals().col(v);
    for (const auto& [joint, weight] : weights) spec.influences[v].push_back({joint, weight});
  }
  // Placement (see the header): the bound mesh's rest frame origin o_s at o_t / k_m.
  Eigen::Matrix3Xd target_world(3, nv);
  for (int v = 0; v < nv; ++v) target_world.col(v) = target_world_from_bind * target_mesh.rest_positions().col(v);
  const CharacterFrame target_frame = ComputeCharacterFrame(target_world);
  const CharacterFrame bound_frame = ComputeCharacterFrame(spec.rest_positions);
  const Eigen::Vector3d shift =
      target_frame.origin * (bound_frame.height / target_frame.height) - bound_frame.origin;
  spec.rest_positions.colwise() += shift;
  aligned.translations[0] += shift;
  ForwardKinematics(source, aligned, &fk);
  for (int j = 0; j < ns; ++j) world[j] = fk.world_rotations[j];
  spec.joint_from_bind.resize(ns);
  for (int j = 0; j < ns; ++j) {
    Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
    world_from_joint.linear() = world[j].toRotationMatrix();
    world_from_joint.translation() = positions[j];
    spec.joint_from_bind[j] = world_from_joint.inverse();
  }
  Status status = SkinnedMesh::Create(source, std::move(spec), &out.mesh);
  if (!status.ok()) return Status::Error("binding the target mesh to the source skeleton: " + status.message());
  out.aligned_pose = std::move(aligned);
  *binding = std::move(out);
  return Status::Ok();
}

}  // namespace mocapsolve
