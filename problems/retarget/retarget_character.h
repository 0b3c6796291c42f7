// RetargetMotionOntoCharacter: one call from a source motion (any skeleton, skinned or
// not) to the same motion on a skinned target character (issue 11 items 2-3); used by
// `mocapsolve retarget` and by the pipeline.
//
// Source with a mesh (a skinned glTF): chapter 4 as it is (retarget_setup.h,
// retarget_clip.h): the source's own surface is tracked.
// Source without a mesh (BVH, ASF/AMC, FBX, or a glTF whose mesh is not wanted): the
// target's mesh is bound to the source skeleton after aligning the rest poses
// (skeleton_binding.h: joint map by names and structure, joint_map.h; bones pointed like
// the target's bind-pose bones, scale by the height ratio, the source's up axis turned to
// +y) and that surface
// is tracked; RetargetClip runs unchanged. So the source may be in cm, CMU units or m,
// Y-up or Z-up, T-pose or A-pose; the output motion is on the target skeleton in its
// units, at the source's frame rate.
//
// Blend mask: unless given, where no target joint is named like a hand, foot, toe or head
// (retarget_setup.h) and the target is a humanoid (humanoid_roles.h), its head, hand, foot
// and toes joints are the position joints (so renaming the joints changes nothing).
//
// Own skeleton: when the source skeleton is the target's (same joints, hierarchy and rest
// offsets up to a scale; own_skeleton.h), whatever the source's kind, the result is the
// source motion on the target's joints (TransferOwnMotion, after the up-axis turn), exact:
// the vertex tracking is not run (its figures are measured at that motion), nor the foot
// plants (the transfer adds no skating), and the notes say so.
//
// IK bones under a floor root (floor_ik_bones.h): when the target has them and the source does
// not drive them (the same bones under the same parents), the whole retarget runs on the
// target with them re-parented under their anchors (same mesh, same world transforms), and
// the result (motion, joint map, position joints, root track) is put back on the target's own
// joints, the IK bones with translation keys; the figures are those of that solve; a note
// names the bones and anchors.
// Limb directions (options.clip.solve.limb_direction_weight > 0, the clip solved): the
// eight limbs found on both sides are asked to point as the source's do (limb_goals.h,
// LimbDirectionResidual), against the vertex tracking; the notes say how many.
// Root motion (options.root_motion): keep, root_bone or in_place (root_motion.h), after
// the solve and the quality figures; the notes say which and the track's length.
//
// Foot plants (options.plant_feet): contacts of the source's foot joints (AutoFootJoints,
// or options.foot_joints) by DetectFootContacts (edit_propagation/foot_contacts.h): height
// above the joint's lowest point <= contact_height * h_s and speed <= contact_speed * h_s
// per second, h_s the source height (mapped joints' vertical extent, or its mesh's
// height). Every foot joint that maps to a target joint (joint_map.h) becomes a plant
// of the per-frame solve (FootPlantResidual, RetargetClipOptions::plant_contacts): from
// the second frame of a contact on, the target joint is held where it was at the first.
// Contacts are detected (for the figures) also with plant_feet off. Skating figures: mean horizontal speed of those joints over the frame pairs in which the
// source joint is in contact, for the source (its joint, times the height ratio, so in the
// target's scale) and the result, in cm/s (target units through its skeleton's unit; the
// target's own units when unknown).
#ifndef MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_CHARACTER_H_
#define MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_CHARACTER_H_

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"
#include "problems/retarget/joint_map.h"
#include "problems/retarget/retarget_clip.h"
#include "problems/retarget/retarget_quality.h"
#include "problems/retarget/retarget_setup.h"
#include "problems/retarget/root_motion.h"

namespace mocapsolve {

// A character as the retargeting sees it (for a glTF: io/gltf_reader.h's GltfCharacter
// gives {&c.skeleton, &c.mesh, c.bind_pose, c.rest_pose}). The pointees must outlive the call.
struct RetargetCharacter {
  const Skeleton* skeleton = nullptr;
  const SkinnedMesh* mesh = nullptr;  // Source: nullptr = skeleton only. Target: required.
  Pose bind_pose;  // The pose of the mesh's bind matrices; empty = RestPose.
  Pose rest_pose;  // The world pose of the file (glTF node defaults); empty = bind_pose.
};

struct CharacterRetargetOptions {
  // setup.{source,target}_world_from_bind and clip.start_pose (when empty: the target's
  // rest pose) are set by the call.
  RetargetSetupOptions setup;
  RetargetClipOptions clip;   // clip.solve.plant_joints / clip.plant_contacts: set by the call.
  std::vector<std::pair<std::string, std::string>> joint_map;  // (source, target) overrides.
  bool plant_feet = true;
  std::vector<std::string> foot_joints;  // Source joints to plant; empty = AutoFootJoints.
  double contact_height = 0.03;  // Source heights above the joint's lowest point.
  double contact_speed = 0.15;   // Source heights per second.
  int first_frame_solves = 5;    // Sets clip.first_frame_solves (see retarget_clip.h).
  // Game-engine root convention, applied last (root_motion.h); the track follows the
  // target's pelvis role (a non-humanoid: FirstBranchingJoint).
  RootMotionOptions root_motion;
  // A skeleton-only source's horizontal root motion scaled by the leg-length ratio over the
  // height ratio before the solve (stride_scale.h); off: the height ratio alone.
  bool stride_to_legs = false;
  // The floor (floor_residual.h) under the target's foot and toes role joints: each kept at
  // or above its rest clearance over y = 0 of the result's world (the source's floor, turned
  // and scaled), weight per sigma of depth; 0 = off. Plant anchors are lifted to it too.
  double floor_weight = 10.0;

  bool IsValid(std::string* error) const;
};

struct CharacterRetargetResult {
  RetargetClipResult clip;  // clip.motion: the result on the target skeleton.
  RetargetSetup setup;
  JointMap joint_map;
  bool skeleton_only = false;
  // The source is the target's own skeleton (own_skeleton.h): the result is the source
  // motion transferred joint by joint (exact), not solved; the feet are not re-planted.
  bool own_skeleton = false;
  double height_ratio = 1.0;        // Target units per source unit.
  double mean_bone_angle_deg = 0.0;  // Skeleton only: aligned rest bones vs the target's.
  std::vector<std::string> plant_joints;  // Target joints planted (none with plant_feet off).
  int contact_samples = 0;                // (joint, frame)s in contact.
  int plant_pairs = 0;                    // (joint, frame pair)s in contact.
  double source_plant_skating_cm_s = 0.0;
  double result_plant_skating_cm_s = 0.0;
  // Limb directions, skating, penetration, self joint error, coverage (retarget_quality.h),
  // measured before the root motion step: below the root, root_bone leaves every world
  // position as it was and in_place shifts them by the removed track (the figures are
  // those in the track's frame).
  RetargetQuality quality;
  RootMotionResult root_motion;  // The track and heading (empty for keep).
  std::vector<std::string> notes;
  double setup_seconds = 0.0;
};

Status RetargetMotionOntoCharacter(const RetargetCharacter& source, const Motion& source_motion,
                                   const RetargetCharacter& target, const CharacterRetargetOptions& options,
                                   CharacterRetargetResult* result,
                                   const RetargetProgressCallback& progress = nullptr);
// The same, taking the source motion over (left empty): the working copy the retarget
// makes of it (turned to the target's up) is made in place, so a caller that needs the
// motion no more does not hold a long take's source twice (1.8 KB per frame of the CMU
// subject's 31 joints). The result is the same as the call above's.
Status RetargetMotionOntoCharacter(const RetargetCharacter& source, Motion&& source_motion,
                                   const RetargetCharacter& target, const CharacterRetargetOptions& options,
                                   CharacterRetargetResult* result,
                                   const RetargetProgressCallback& progress = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_RETARGET_RETARGET_CHARACTER_H_
