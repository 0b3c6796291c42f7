#include "problems/retarget/floor_ik_bones.h"

#include <limits>
#include <utility>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {
namespace {

// `pose` of `from` re-expressed on `to` (to_joint -> from_joint in from_of_to): local rotations
// and translations copied, except at the joints `moved` (indices on `to`), whose parent differs:
// there t = Q_p^T (x_j - x_p) and R = R_rest^-1 Q_p^-1 Q_j from the world transforms of `from`.
Pose ReparentedPose(const Skeleton& from, const Skeleton& to, const std::vector<int>& from_of_to,
                    const std::vector<bool>& moved, const Pose& pose) {
  FkData fk(from);
  ForwardKinematics(from, pose, &fk);
  Pose out;
  out.translations.resize(to.num_joints());
  out.rotations.resize(to.num_joints());
  for (int k = 0; k < to.num_joints(); ++k) {
    const int j = from_of_to[k];
    if (!moved[k]) {
      out.translations[k] = pose.translations[j];
      out.rotations[k] = pose.rotations[j];
      continue;
    }
    const int p = from_of_to[to.parent(k)];
    const Eigen::Quaterniond& q_p = fk.world_rotations[p];
    out.translations[k] = q_p.conjugate() * (fk.world_positions[j] - fk.world_positions[p]);
    out.rotations[k] = (to.rest_rotation(k).conjugate() * q_p.conjugate() * fk.world_rotations[j]).normalized();
  }
  return out;
}

}  // namespace

std::string FloorIkBones::Describe(const Skeleton& skeleton) const {
  std::string text;
  for (size_t k = 0; k < bones.size(); ++k) {
    if (k > 0) text += ", ";
    text += skeleton.name(bones[k]) + " on " + skeleton.name(anchors[k]);
  }
  return text;
}

FloorIkBones FindFloorIkBones(const Skeleton& skeleton, const Vector3dVector& x, const HumanoidRoles& roles,
                              const SkinnedMesh* mesh) {
  FloorIkBones ik;
  const int pelvis = roles.humanoid ? roles.Find("pelvis") : -1;
  if (pelvis <= 0 || static_cast<int>(x.size()) != skeleton.num_joints()) return ik;
  std::vector<bool> floor(skeleton.num_joints(), false);
  for (int a = skeleton.parent(pelvis); a >= 0; a = skeleton.parent(a)) floor[a] = true;
  std::vector<int> heaviest;  // Per vertex of the pelvis' subtree: its heaviest joint; found when needed.
  // Anchors are body joints: where the weights are known, joints whose subtree carries some
  // (not Rigify's ORG- copies of a limb, which lie on the skinned DEF- chain and tie with it).
  std::vector<bool> body(skeleton.num_joints(), true);
  if (mesh != nullptr && mesh->num_joints() == skeleton.num_joints() && mesh->num_vertices() > 0) {
    std::vector<bool> carries(skeleton.num_joints(), false);
    for (int k = 0; k < mesh->weight_end(mesh->num_vertices() - 1); ++k) {
      if (mesh->weight(k) > 0.0) carries[mesh->weight_joint(k)] = true;
    }
    for (int j = skeleton.num_joints() - 1; j > 0; --j) {
      if (carries[j]) carries[skeleton.parent(j)] = true;
    }
    body = carries;
  }
  for (int j = 1; j < skeleton.num_joints(); ++j) {
    const int p = skeleton.parent(j);
    if (!floor[p] || skeleton.IsAncestorOrSelf(j, pelvis)) continue;
    double nearest = std::numeric_limits<double>::infinity();
    int anchor = -1;
    for (int a = pelvis; a < skeleton.subtree_end(pelvis); ++a) {
      if (!body[a]) continue;
      const double d = (x[j] - x[a]).norm();
      if (d < nearest) nearest = d, anchor = a;
    }
    if (mesh != nullptr && mesh->num_joints() == skeleton.num_joints()) {
      if (heaviest.empty()) {
        heaviest.assign(mesh->num_vertices(), -1);
        for (int v = 0; v < mesh->num_vertices(); ++v) {
          double w = 0.0;
          for (int k = mesh->weight_begin(v); k < mesh->weight_end(v); ++k) {
            if (mesh->weight(k) > w) w = mesh->weight(k), heaviest[v] = mesh->weight_joint(k);
          }
        }
      }
      for (int v = 0; v < mesh->num_vertices(); ++v) {
        const int a = heaviest[v];
        if (a < 0 || !skeleton.IsAncestorOrSelf(pelvis, a)) continue;
        const double d = (x[j] - mesh->rest_positions().col(v)).norm();
        if (d < nearest) nearest = d, anchor = a;
      }
    }
    if (anchor >= 0 && nearest < (x[j] - x[p]).norm()) {
      ik.bones.push_back(j);
      ik.anchors.push_back(anchor);
    } else {
      floor[j] = true;
    }
  }
  return ik;
}

Status MakeFloorIkSolveCharacter(const Skeleton& skeleton, const SkinnedMesh& mesh, const Pose& bind_pose,
                                 const Pose& rest_pose, const FloorIkBones& ik, FloorIkSolveCharacter* solve) {
  const int n = skeleton.num_joints();
  if (mesh.num_joints() != n || static_cast<int>(bind_pose.rotations.size()) != n ||
      static_cast<int>(rest_pose.rotations.size()) != n || ik.bones.size() != ik.anchors.size()) {
    return Status::Error("floor IK bones: the mesh or poses do not fit the skeleton");
  }
  std::vector<int> new_parent(n);
  std::vector<bool> is_ik(n, false);
  for (int j = 0; j < n; ++j) new_parent[j] = skeleton.parent(j);
  for (size_t k = 0; k < ik.bones.size(); ++k) {
    new_parent[ik.bones[k]] = ik.anchors[k];
    is_ik[ik.bones[k]] = true;
  }
  // Preorder of the new tree: an anchor's own children first, then its IK bones.
  std::vector<std::vector<int>> children(n);
  for (int pass = 0; pass < 2; ++pass) {
    for (int j = 1; j < n; ++j) {
      if (is_ik[j] == (pass == 1)) children[new_parent[j]].push_back(j);
    }
  }
  std::vector<int>& order = solve->character_of_solve;
  order.clear();
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const int j = stack.back();
    stack.pop_back();
    order.push_back(j);
    for (auto c = children[j].rbegin(); c != children[j].rend(); ++c) stack.push_back(*c);
  }
  if (static_cast<int>(order.size()) != n) return Status::Error("floor IK bones: an anchor lies inside its IK bone");
  solve->solve_of_character.assign(n, -1);
  for (int k = 0; k < n; ++k) solve->solve_of_character[order[k]] = k;
  const std::vector<int>& solve_of = solve->solve_of_character;

  std::vector<bool> moved(n, false);  // On the solve skeleton.
  std::vector<JointSpec> specs;
  for (int k = 0; k < n; ++k) {
    const int j = order[k];
    specs.push_back(skeleton.joint(j));
    specs.back().parent = k == 0 ? -1 : solve_of[new_parent[j]];
    moved[k] = is_ik[j];
  }
  // Offsets of the IK bones: their rest translations relative to the anchors (a first skeleton
  // with the old offsets serves to compute them; rest rotations and order are already final).
  Skeleton draft;
  std::vector<EndSite> end_sites = skeleton.end_sites();
  for (EndSite& e : end_sites) e.parent = solve_of[e.parent];
  Status status = Skeleton::Create(specs, end_sites, skeleton.unit(), &draft);
  if (!status.ok()) return status;
  solve->rest_pose = ReparentedPose(skeleton, draft, order, moved, rest_pose);
  for (int k = 0; k < n; ++k) {
    if (moved[k]) specs[k].offset = solve->rest_pose.translations[k];
  }
  status = Skeleton::Create(std::move(specs), std::move(end_sites), skeleton.unit(), &solve->skeleton);
  if (!status.ok()) return status;
  solve->bind_pose = ReparentedPose(skeleton, solve->skeleton, order, moved, bind_pose);

  SkinnedMeshSpec spec;
  spec.rest_positions = mesh.rest_positions();
  spec.rest_normals = mesh.rest_normals();
  spec.texcoords = mesh.texcoords();
  spec.influences.resize(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    for (int k = mesh.weight_begin(v); k < mesh.weight_end(v); ++k) {
      spec.influences[v].push_back({solve_of[mesh.weight_joint(k)], mesh.weight(k)});
    }
  }
  for (int k = 0; k < n; ++k) spec.joint_from_bind.push_back(mesh.joint_from_bind(order[k]));
  return SkinnedMesh::Create(solve->skeleton, std::move(spec), &solve->mesh);
}

Pose FloorIkPoseOnSolveCharacter(const Skeleton& skeleton, const FloorIkBones& ik,
                                 const FloorIkSolveCharacter& solve, const Pose& pose) {
  std::vector<bool> moved(skeleton.num_joints(), false);
  for (int j : ik.bones) moved[solve.solve_of_character[j]] = true;
  return ReparentedPose(skeleton, solve.skeleton, solve.character_of_solve, moved, pose);
}

Pose FloorIkPoseOnCharacter(const Skeleton& skeleton, const FloorIkBones& ik, const FloorIkSolveCharacter& solve,
                            const Pose& solve_pose) {
  std::vector<bool> moved(skeleton.num_joints(), false);
  for (int j : ik.bones) moved[j] = true;
  return ReparentedPose(solve.skeleton, skeleton, solve.solve_of_character, moved, solve_pose);
}

Motion FloorIkMotionOnCharacter(const Skeleton& skeleton, const FloorIkBones& ik, const FloorIkSolveCharacter& solve,
                                const Motion& motion) {
  Motion out;
  out.frame_rate = motion.frame_rate;
  out.frames.reserve(motion.frames.size());
  for (const Pose& pose : motion.frames) out.frames.push_back(FloorIkPoseOnCharacter(skeleton, ik, solve, pose));
  return out;
}

}  // namespace mocapsolve
