#include "problems/retarget/synthetic_skinned_character.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glog/logging.h>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"

namespace mocapsolve {

SkinnedMesh MakeCylinderCharacter(const Skeleton& skeleton,
                                  const CylinderCharacterOptions& options) {
  CHECK_GE(options.rings, 2);
  CHECK_GE(options.segments, 3);
  const int nj = skeleton.num_joints();
  FkData bind(skeleton);
  ForwardKinematics(skeleton, RestPose(skeleton), &bind);
  double min_y = std::numeric_limits<double>::infinity(), max_y = -min_y;
  for (int j = 0; j < nj; ++j) {
    min_y = std::min(min_y, bind.world_positions[j].y());
    max_y = std::max(max_y, bind.world_positions[j].y());
  }
  const Vector3dVector end_sites = EndSitePositions(skeleton, bind);
  const double radius = options.radius * std::max(max_y - min_y, 1e-9);

  SkinnedMeshSpec spec;
  std::vector<Eigen::Vector3d> positions, normals;
  for (int j = 0; j < nj; ++j) {
    const Eigen::Vector3d start = bind.world_positions[j];
    Eigen::Vector3d end = start;
    bool found = false;
    for (int c = j + 1; c < nj && !found; ++c) {
      if (skeleton.parent(c) == j && (bind.world_positions[c] - start).norm() > 1e-9) {
        end = bind.world_positions[c];
        found = true;
      }
    }
    for (size_t e = 0; e < end_sites.size() && !found; ++e) {
      if (skeleton.end_sites()[e].parent == j && (end_sites[e] - start).norm() > 1e-9) {
        end = end_sites[e];
        found = true;
      }
    }
    const int parent = skeleton.parent(j);
    if (!found && parent >= 0) {
      const Eigen::Vector3d along = start - bind.world_positions[parent];
      end = start + (along.norm() > 1e-9 ? 0.3 * along : Eigen::Vector3d(0, 0.05, 0));
      found = true;
    }
    if (!found) continue;
    const Eigen::Vector3d axis = (end - start).normalized();
    const Eigen::Vector3d helper =
        std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d u = axis.cross(helper).normalized();
    const Eigen::Vector3d v = axis.cross(u);
    auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& n, double t) {
      positions.push_back(p);
      normals.push_back(n);
      const double blend = parent >= 0 ? std::max(0.0, 0.5 - 2.0 * t) : 0.0;
      std::vector<SkinInfluence> influences = {{j, 1.0 - blend}};
      if (blend > 0.0) influences.push_back({parent, blend});
      spec.influences.push_back(influences);
    };
    for (int r = 0; r < options.rings; ++r) {
      const double t = (r + 0.5) / options.rings;
      const Eigen::Vector3d centre = start + t * (end - start);
      for (int s = 0; s < options.segments; ++s) {
        const double angle = 2.0 * kPi * (s + 0.5 * (r % 2)) / options.segments;
        const Eigen::Vector3d n = std::cos(angle) * u + std::sin(angle) * v;
        add(centre + radius * n, n, t);
      }
    }
    // End cap: a small disc of vertices at the far end, normals along the bone.
    for (int s = 0; s < options.segments / 2; ++s) {
      const double angle = 4.0 * kPi * s / options.segments;
      add(end + 0.5 * radius * (std::cos(angle) * u + std::sin(angle) * v), axis, 1.0);
    }
  }
  const int nv = static_cast<int>(positions.size());
  spec.rest_positions.resize(3, nv);
  spec.rest_normals.resize(3, nv);
  for (int i = 0; i < nv; ++i) {
    spec.rest_positions.col(i) = positions[i];
    spec.rest_normals.col(i) = normals[i];
  }
  for (int j = 0; j < nj; ++j) {
    Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
    world_from_joint.linear() = bind.world_rotations[j].toRotationMatrix();
    world_from_joint.translation() = bind.world_positions[j];
    spec.joint_from_bind.push_back(world_from_joint.inverse());
  }
  SkinnedMesh mesh;
  const Status status = SkinnedMesh::Create(skeleton, std::move(spec), &mesh);
  CHECK(status.ok()) << status.message();
  return mesh;
}

Skeleton ScaleSkeleton(const Skeleton& skeleton, double factor) {
  std::vector<JointSpec> joints;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    joints.push_back(skeleton.joint(j));
    joints.back().offset *= factor;
  }
  std::vector<EndSite> end_sites = skeleton.end_sites();
  for (EndSite& e : end_sites) e.offset *= factor;
  Skeleton scaled;
  const Status status = Skeleton::Create(joints, end_sites, skeleton.unit(), &scaled);
  CHECK(status.ok()) << status.message();
  return scaled;
}

Motion ScaleMotion(const Motion& motion, double factor) {
  Motion scaled = motion;
  for (Pose& pose : scaled.frames) {
    for (Eigen::Vector3d& t : pose.translations) t *= factor;
  }
  return scaled;
}

}  // namespace mocapsolve
