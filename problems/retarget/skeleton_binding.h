// Giving a skeleton-only source a surface (issue 11 item 2): the TARGET's own mesh bound
// to the SOURCE skeleton, so that RetargetClip (chapter 4's vertex tracking) runs
// unchanged on a BVH / ASF-AMC / FBX / skinless glTF source.
//
// Why the target's mesh: it is the surface the result must move, so tracking a copy of it
// carried by the source skeleton asks exactly "move this surface as the source's bones
// move it"; the mapping between the two meshes (mesh_mapping.h) becomes near-identity and
// no generic proxy (capsules) has to be tuned per character. Measured alternatives: see the
// README ("Mesh retargeting").
//
// 1. Joint map (joint_map.h): source joint m(b) for target joint b, by names.
// 2. Up axis: U = the rotation taking the source world's up axis to +Y, the up axis being
//    the coordinate axis (+-x, +-y, +-z) nearest to the mean over the clip of the vector
//    from the lowest to the highest mapped joint (lowest and highest in the target's bind
//    pose: toes/feet to head). The source motion is turned by U (RotateMotionWorld); a
//    Y-up source has U = I.
// 3. Rest-pose alignment. With p_j the source rest-pose joint positions (FK of RestPose)
//    and q_b the target's bind-pose joint positions in its world (target_world_from_bind
//    times FK of the bind pose), per mapped source joint j in preorder, the vectors
//    u_c = D_parent(j) (p_c - p_j) and v_c = q_m(c) - q_m(j) over j's mapped children c
//    (the mapped joints whose nearest mapped proper ancestor is j) give the correction
//        E_j = argmin_R sum |R u^_c - v^_c|^2   (Kabsch; the minimal rotation for one child)
//    and D_j = E_j D_parent(j) (unmapped joints and mapped leaves: D_j = D_parent(j), so
//    they follow rigidly). Above the first mapped joint D = S U: U (step 2) and S, the
//    minimal rotation taking the start pose's body axis (the target's highest mapped joint,
//    the head, against the mapped joints' centroid) to the target bind pose's. The first
//    mapped joint (the pelvis) takes E = C of pelvis_rest_correction.h instead of Kabsch:
//    a turn about up, the tilt kept only where both rigs' pelvis children are one set turned
//    (where they start is each rig's design: RobotExpressive's Body -> Abdomen leans 40
//    degrees back; a tilt taken from them tilts whatever rides on the pelvis through the
//    take). The aligned pose has world rotations D_j R^rest_j: every mapped bone below the
//    pelvis points where the target's bind-pose bone points, which absorbs T vs A pose,
//    facing and the up axis; the pelvis's own bones are left out of the bone angles when
//    its tilt is not (fully) kept. The upright pose C S U times the start pose is kept
//    (upright_world, upright_positions) for retarget_quality.h's torso orientation.
//    Twist about a bone with one mapped child is left as in the source's rest pose.
//    Where the u_c are (nearly) parallel (CMU's thorax: neck and clavicles start at one
//    point), the minimal rotation of their mean replaces Kabsch, whose twist about them
//    would be arbitrary. If the rest pose leaves a mapped bone more than 45 degrees off
//    (CMU FBX files: every bone of the rest pose along +y, the posture is all in the
//    animation) or S turns it more than 30 degrees (it does not stand: CesiumMan's node
//    rest lies bent in a plane), eight frames of the motion are tried as the start instead
//    and the one with the lowest mean bone angle among those that stand is kept (noted).
// 4. Scale k = h_t / h_s with h the vertical extent of the mapped joints (target bind
//    pose; aligned source pose): the source's units (cm, CMU's 1/0.45 in, m) disappear.
// 6. Placement: the aligned pose and the bound mesh are translated so that the bound
//    mesh's rest frame origin (mesh_mapping.h: feet level) is o_t / k_m, with o_t the
//    target's and k_m = h_t / h_s the ratio of the two meshes' heights (the setup's
//    scale). The goals of retarget_setup.h, o_t + k_m (p - o_s), are then k_m p: the
//    source world maps onto the target's scaled about the origin (floors at y = 0, the
//    mocap and glTF convention; the source's path is kept, scaled), and a character's own
//    motion maps onto itself.
// 5. Binding. Target vertex x (world, bind pose) with weights w_b: each influence b is
//    replaced by source joint m(a(b)), a(b) = b or its nearest mapped ancestor (fingers,
//    head tops; the root-most mapped target joint when none), and the vertex is snapped
//    onto the source's bones:
//        x_s = sum_b w_b (P_m(a(b)) + (x - q_a(b)) / k),   n_s = n,
//    with P the aligned source joint positions; the aligned pose is the bind pose
//    (joint_from_bind_j = (D_j R^rest_j, P_j)^-1). Snapping per influence keeps a hand's
//    vertices around the source's hand when the two skeletons' proportions differ.
// Errors: fewer than kMinMappedJoints joints mapped (the message lists the target's
// unmapped joints), a zero vertical extent.
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_SKELETON_BINDING_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_SKELETON_BINDING_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/joint_map.h"

namespace mocapsolve {

constexpr int kMinMappedJoints = 5;

struct SkeletonBinding {
  Eigen::Matrix3d up = Eigen::Matrix3d::Identity();  // U: source world -> Y up.
  Pose aligned_pose;    // Source skeleton posed like the target's bind pose (Y-up world).
  SkinnedMesh mesh;     // The target mesh on the source skeleton (source units).
  double scale = 1.0;   // k = target units per source unit.
  double source_height = 0.0;  // h_s, source units.
  double mean_bone_angle_deg = 0.0;  // Aligned source bones vs the target's, mapped bones.
  double max_bone_angle_deg = 0.0;
  std::string worst_bone;            // Target joint of the worst bone.
  double pelvis_residual_deg = 0.0;  // The pelvis children's fit residual r (pelvis_rest_correction.h).
  double pelvis_tilt_kept = 0.0;     // w: 1 = its full rotation, 0 = a turn about up only.
  // The source's start pose (its rest, or the frame the alignment started from) stood up
  // (U) and turned by the pelvis's correction C: per source joint its world rotation where
  // it stands in the target's bind pose when both rest poses are upright
  // (retarget_quality.h's torso orientation).
  std::vector<Eigen::Quaterniond> upright_world;
  Vector3dVector upright_positions;  // The same pose's joint positions (only differences count).
  std::vector<std::string> notes;
};

// The motion with its world turned by `rotation` (root translation and rotation).
Motion RotateMotionWorld(const Skeleton& skeleton, const Motion& motion, const Eigen::Matrix3d& rotation);
// The same in place.
void RotateMotionWorld(const Skeleton& skeleton, const Eigen::Matrix3d& rotation, Motion* motion);

// `source_motion` (may be empty: then U from the rest pose) decides the up axis.
Status BindTargetMeshToSource(const Skeleton& source, const Motion& source_motion, const Skeleton& target,
                              const SkinnedMesh& target_mesh, const Pose& target_bind_pose,
                              const Eigen::Matrix3d& target_world_from_bind, const JointMap& map,
                              SkeletonBinding* binding);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_SKELETON_BINDING_H_
