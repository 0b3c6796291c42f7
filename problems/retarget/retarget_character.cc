#include "problems/retarget/retarget_character.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "kinematics/forward_kinematics.h"
#include "problems/edit_propagation/foot_contacts.h"
#include "problems/retarget/floor_ik_bones.h"
#include "problems/retarget/foot_clearance.h"
#include "problems/retarget/role_sides.h"
#include "problems/retarget/limb_goals.h"
#include "problems/retarget/own_skeleton.h"
#include "problems/retarget/skeleton_binding.h"
#include "problems/retarget/stride_scale.h"

namespace mocapsolve {
namespace {

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, format, a, b, c);
  return buffer;
}

// The inputs the retargeting needs: valid options, a source skeleton, a target skeleton with
// a skinned mesh and a non-empty motion that fits the source skeleton.
Status CheckInputs(const RetargetCharacter& source, const Motion& source_motion, const RetargetCharacter& target,
                   const CharacterRetargetOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("retarget options: " + error);
  if (source.skeleton == nullptr || target.skeleton == nullptr || target.mesh == nullptr) {
    return Status::Error("retarget: the source needs a skeleton, the target a skeleton and a skinned mesh");
  }
  if (source_motion.num_frames() == 0) return Status::Error("retarget: the source motion has no frames");
  for (const Pose& pose : source_motion.frames) {
    if (static_cast<int>(pose.rotations.size()) != source.skeleton->num_joints()) {
      return Status::Error("retarget: the source motion does not fit its skeleton");
    }
  }
  return Status::Ok();
}

// Blend mask: where no target joint is named like a hand, foot, toe or head, the
// humanoid roles say which joints those are (noted). Given position joints are kept.
void AddHumanoidPositionJoints(const Skeleton& target_skeleton, const JointMap& joint_map,
                               RetargetSetupOptions* setup_options, std::vector<std::string>* notes) {
  if (!setup_options->position_joints.empty() || !joint_map.target_roles.humanoid) return;
  bool named = false;
  for (int j = 0; j < target_skeleton.num_joints() && !named; ++j) {
    std::string name = target_skeleton.name(j);
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    for (std::string pattern : setup_options->position_name_patterns) {
      std::transform(pattern.begin(), pattern.end(), pattern.begin(), [](unsigned char c) { return std::tolower(c); });
      named = named || name.find(pattern) != std::string::npos;
    }
  }
  if (named) return;
  for (const auto& [role, joint] : joint_map.target_roles.roles) {
    if (role == "head" || role.find("_hand") != std::string::npos || role.find("_foot") != std::string::npos ||
        role.find("_toes") != std::string::npos) {
      setup_options->position_joints.push_back(target_skeleton.name(joint));
    }
  }
  notes->push_back("blend mask: no target joint named like a hand, foot, toe or head; the humanoid roles "
                   "head, hands, feet and toes are tracked by position");
}

// The source's foot contacts, over its foot joints (options.foot_joints, else AutoFootJoints)
// that map to a target joint; thresholds relative to `source_height`. None (noted) when no
// foot joint maps or the motion has no frame rate.
Status DetectMappedFootContacts(const Skeleton& source_skeleton, const Motion& motion, const JointMap& joint_map,
                                const CharacterRetargetOptions& options, double source_height,
                                FootContacts* contacts, std::vector<std::string>* notes) {
  FootContactOptions contact_options;
  for (const std::string& name : options.foot_joints) {
    const int j = source_skeleton.FindJoint(name);
    if (j < 0) return Status::Error("retarget: foot joint '" + name + "' is not a source joint");
    contact_options.joints.push_back(j);
  }
  if (contact_options.joints.empty()) contact_options.joints = AutoFootJoints(source_skeleton);
  std::vector<int> mapped;
  for (int j : contact_options.joints) {
    if (joint_map.target_of_source[j] >= 0) mapped.push_back(j);
  }
  contact_options.joints = mapped;
  contact_options.height_threshold = options.contact_height * source_height;
  contact_options.speed_threshold = options.contact_speed * source_height;
  contact_options.up_axis = 1;
  if (mapped.empty()) {
    notes->push_back("no foot contacts: no source foot joint maps to a target joint");
  } else if (!(motion.frame_rate > 0.0)) {
    notes->push_back("no foot contacts: the source has no frame rate");
  } else {
    Status status = DetectFootContacts(source_skeleton, motion, contact_options, contacts);
    if (!status.ok()) return Status::Error("retarget: foot contacts: " + status.message());
  }
  return Status::Ok();
}

// Skating of the plant joints (target joints `contact_targets` in the result) while the
// source's are in contact: mean horizontal speeds, cm/s when the target's unit is known.
void MeasurePlantSkating(const Skeleton& target_skeleton, const Motion& motion, const FootContacts& contacts,
                         const std::vector<int>& contact_targets, CharacterRetargetResult* out) {
  if (contacts.joints.empty()) return;
  const double cm = target_skeleton.unit().known() ? 100.0 * target_skeleton.unit().metres_per_unit : 1.0;
  // The result's positions of the plant joints only ([k][f]), not of every joint (Xbot's
  // 65: 1.6 KB per frame of a long take).
  const int frames = out->clip.motion.num_frames();
  std::vector<Vector3dVector> result_positions(contacts.joints.size(), Vector3dVector(frames));
  FkData fk(target_skeleton);
  for (int f = 0; f < frames; ++f) {
    ForwardKinematics(target_skeleton, out->clip.motion.frames[f], &fk);
    for (size_t k = 0; k < contacts.joints.size(); ++k) result_positions[k][f] = fk.world_positions[contact_targets[k]];
  }
  double source_sum = 0.0, result_sum = 0.0;
  int pairs = 0;
  for (size_t k = 0; k < contacts.joints.size(); ++k) {
    for (int f = 1; f < motion.num_frames(); ++f) {
      if (!contacts.in_contact[k][f - 1] || !contacts.in_contact[k][f]) continue;
      const Eigen::Vector3d a = contacts.positions[k][f] - contacts.positions[k][f - 1];
      const Eigen::Vector3d b = result_positions[k][f] - result_positions[k][f - 1];
      source_sum += std::hypot(a.x(), a.z()) * out->height_ratio;
      result_sum += std::hypot(b.x(), b.z());
      ++pairs;
    }
  }
  out->plant_pairs = pairs;
  if (pairs > 0) {
    out->source_plant_skating_cm_s = source_sum / pairs * motion.frame_rate * cm;
    out->result_plant_skating_cm_s = result_sum / pairs * motion.frame_rate * cm;
  }
}

// The limb direction term (limb_goals.h) when its weight is on and the clip is solved:
// the target's limbs and their goals per frame (noted); off otherwise.
void SetLimbGoals(const Skeleton& source, const Motion& motion, const Skeleton& target, const Pose& target_rest,
                  const CharacterRetargetResult& out, RetargetClipOptions* clip, std::vector<std::string>* notes) {
  clip->solve.limbs.clear();
  clip->limb_goals.clear();
  if (!(clip->solve.limb_direction_weight > 0.0) || !clip->run_solver) return;
  LimbGoals goals = ComputeLimbGoals(out.joint_map, source, motion, target, target_rest, out.setup);
  if (goals.limbs.empty()) {
    notes->push_back("limb directions: no limb found on both skeletons, the term is off");
    return;
  }
  clip->solve.limbs = goals.limbs;
  clip->limb_goals = std::move(goals.directions);
  notes->push_back(std::to_string(goals.limbs.size()) + " limbs asked to point as the source's (weight " +
                   Format("%g", clip->solve.limb_direction_weight) + ")");
}

// Stride: the source root's horizontal motion scaled by the leg-length ratio over the
// height ratio (stride_scale.h), when both skeletons are humanoids with legs (noted).
void ScaleStrideToLegs(const Skeleton& source, const Skeleton& target, const JointMap& map, double height_ratio,
                       Motion* motion, std::vector<std::string>* notes) {
  std::vector<std::pair<int, int>> source_legs, target_legs;  // (thigh, foot) per side, as the map links them.
  for (const std::string side : {"left_", "right_"}) {
    int thigh[2] = {-1, -1}, foot[2] = {-1, -1};
    for (const JointMapRole& role : map.roles) {
      if (role.role == side + "thigh") thigh[0] = role.source, thigh[1] = role.target;
      if (role.role == side + "foot") foot[0] = role.source, foot[1] = role.target;
    }
    source_legs.emplace_back(thigh[0], foot[0]);
    target_legs.emplace_back(thigh[1], foot[1]);
  }
  const double source_leg = LegLength(source, source_legs), target_leg = LegLength(target, target_legs);
  if (!(source_leg > 0.0) || !(target_leg > 0.0) || !(height_ratio > 0.0)) return;
  const double factor = target_leg / source_leg / height_ratio;
  ScaleRootStride(factor, motion);
  notes->push_back(Format("stride scaled by the leg-length ratio: %.3g of the height ratio's (legs %.3g, height "
                          "ratio %.3g)", factor, target_leg / source_leg, height_ratio));
}

}  // namespace

bool CharacterRetargetOptions::IsValid(std::string* error) const {
  if (!clip.solve.IsValid(error)) return false;
  if (!(contact_height > 0.0) || !(contact_speed > 0.0)) {
    return *error = "contact height and speed must be > 0", false;
  }
  if (!(clip.contact_height > 0.0)) return *error = "skating contact height must be > 0", false;
  if (!(floor_weight >= 0.0) || !std::isfinite(floor_weight)) return *error = "floor weight must be >= 0", false;
  if (setup.subsample.ratio < 1) return *error = "subsample ratio must be >= 1", false;
  if (first_frame_solves < 1) return *error = "first frame solves must be >= 1", false;
  if (!(root_motion.smoothing_seconds >= 0.0)) return *error = "root motion smoothing must be >= 0", false;
  return true;
}

namespace {

// The retarget onto a character as the solve sees it (after CheckInputs). `consumed`:
// null, or source_motion itself, which the working copy is then moved from (after which
// source_motion is not read).
Status RetargetOntoSolveCharacter(const RetargetCharacter& source, const Motion& source_motion, Motion* consumed,
                                  const RetargetCharacter& target, const CharacterRetargetOptions& options,
                                  CharacterRetargetResult* result, const RetargetProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Skeleton& target_skeleton = *target.skeleton;
  const Pose target_bind = target.bind_pose.rotations.empty() ? RestPose(target_skeleton) : target.bind_pose;
  const Pose target_rest = target.rest_pose.rotations.empty() ? target_bind : target.rest_pose;
  CharacterRetargetResult out;
  out.skeleton_only = source.mesh == nullptr;

  const Pose source_bind = source.bind_pose.rotations.empty() ? RestPose(*source.skeleton) : source.bind_pose;
  // A skeleton-only source's rest pose may be no natural pose: its first frame is the other.
  const Pose& source_other = !source.rest_pose.rotations.empty() ? source.rest_pose : source_motion.frames[0];
  Status map_status = BuildJointMap(StandingSkeleton(*source.skeleton, source_bind, source.mesh, source_other),
                                    StandingSkeleton(target_skeleton, target_bind, target.mesh, target_rest),
                                    options.joint_map, &out.joint_map);
  if (!map_status.ok()) return map_status;
  if (out.skeleton_only && out.joint_map.num_mapped() < kMinMappedJoints) {
    return Status::Error("the source and target skeletons are too different to map (" +
                         std::to_string(out.joint_map.num_mapped()) + " joints map, need " +
                         std::to_string(kMinMappedJoints) + "): source: " + out.joint_map.Found(true) +
                         "; target: " + out.joint_map.Found(false) + " (give a joint map)");
  }
  out.notes.push_back(JointMapNote(out.joint_map));
  double own_scale = 1.0;
  out.own_skeleton = IsSameSkeleton(*source.skeleton, target_skeleton, out.joint_map, &own_scale);

  RetargetSetupOptions setup_options = options.setup;
  setup_options.target_world_from_bind = WorldFromBindRotation(target_skeleton, target_bind, target_rest);
  Motion motion;
  const SkinnedMesh* source_mesh = source.mesh;
  SkeletonBinding binding;
  double source_height = 0.0;
  if (out.skeleton_only) {
    Status status = BindTargetMeshToSource(*source.skeleton, source_motion, target_skeleton, *target.mesh,
                                           target_bind, setup_options.target_world_from_bind, out.joint_map,
                                           &binding);
    if (!status.ok()) return status;
    if (consumed != nullptr) {
      motion = std::move(*consumed);
      RotateMotionWorld(*source.skeleton, binding.up, &motion);
    } else {
      motion = RotateMotionWorld(*source.skeleton, source_motion, binding.up);
    }
    if (!out.own_skeleton && options.stride_to_legs) {
      ScaleStrideToLegs(*source.skeleton, target_skeleton, out.joint_map, binding.scale, &motion, &out.notes);
    }
    source_mesh = &binding.mesh;
    setup_options.source_world_from_bind = Eigen::Matrix3d::Identity();
    source_height = binding.source_height;
    out.mean_bone_angle_deg = binding.mean_bone_angle_deg;
    for (const std::string& note : binding.notes) out.notes.push_back(note);
    out.notes.push_back(std::to_string(out.joint_map.num_mapped()) + " joints mapped; rest poses aligned: " +
                        Format("mean bone angle %.1f deg, worst %.1f deg (", binding.mean_bone_angle_deg,
                               binding.max_bone_angle_deg) +
                        binding.worst_bone + Format("); pelvis children fit %.1f deg, its tilt kept %.0f %%",
                                                    binding.pelvis_residual_deg, 100.0 * binding.pelvis_tilt_kept));
  } else {
    const Pose bind = source.bind_pose.rotations.empty() ? RestPose(*source.skeleton) : source.bind_pose;
    setup_options.source_world_from_bind =
        WorldFromBindRotation(*source.skeleton, bind, source.rest_pose.rotations.empty() ? bind : source.rest_pose);
    motion = consumed != nullptr ? std::move(*consumed) : source_motion;
  }
  // The facings of both meshes signed by the humanoid roles' sides (role_sides.h).
  setup_options.target_left = LeftOfCharacter(target_skeleton, *target.mesh, out.joint_map.target_roles,
                                              setup_options.target_world_from_bind);
  setup_options.source_left = LeftOfCharacter(*source.skeleton, *source_mesh, out.joint_map.source_roles,
                                              setup_options.source_world_from_bind);
  AddHumanoidPositionJoints(target_skeleton, out.joint_map, &setup_options, &out.notes);
  // Every body part of the source's mesh gets its quota of samples (vertex_subsampling.h).
  const std::vector<int> source_parts = BodyParts(*source.skeleton, out.joint_map.source_roles);
  setup_options.source_parts.resize(source_mesh->num_vertices());
  for (int v = 0; v < source_mesh->num_vertices(); ++v) {
    const int j = DominantJoint(*source_mesh, v);
    setup_options.source_parts[v] = j >= 0 ? source_parts[j] : -1;
  }
  setup_options.same_vertices = setup_options.same_vertices || out.skeleton_only;
  Status status = BuildRetargetSetup(*source_mesh, target_skeleton, *target.mesh, setup_options, &out.setup);
  if (!status.ok()) return status;
  for (const std::string& note : out.setup.notes) out.notes.push_back(note);
  out.height_ratio = out.setup.scale;
  if (!out.skeleton_only) source_height = out.setup.source_frame.height;

  RetargetClipOptions clip = options.clip;
  if (clip.start_pose.rotations.empty()) clip.start_pose = target_rest;
  bool plant_feet = options.plant_feet;
  if (out.own_skeleton) {
    clip.warm_start = TransferOwnMotion(*source.skeleton, motion, target_skeleton, out.joint_map, own_scale);
    clip.run_solver = false;
    plant_feet = false;
    out.notes.push_back("the source is the target's own skeleton (same joints, hierarchy and rest offsets" +
                        (std::abs(own_scale - 1.0) > 1e-9 ? Format(", scale %g", own_scale) : std::string()) +
                        "): its motion is transferred joint by joint, exactly (no vertex solve, no re-planting)");
  }
  clip.first_frame_solves = options.first_frame_solves;
  clip.solve.plant_joints.clear();
  clip.plant_contacts.clear();
  FootContacts contacts;
  status = DetectMappedFootContacts(*source.skeleton, motion, out.joint_map, options, source_height, &contacts,
                                    &out.notes);
  if (!status.ok()) return status;
  std::vector<int> contact_targets;  // Target joint of each contact joint.
  for (size_t k = 0; k < contacts.joints.size(); ++k) {
    const int t = out.joint_map.target_of_source[contacts.joints[k]];
    contact_targets.push_back(t);
    if (!plant_feet) continue;  // Contacts for the skating figures only.
    clip.solve.plant_joints.push_back(t);
    clip.plant_contacts.push_back(contacts.in_contact[k]);
    out.plant_joints.push_back(target_skeleton.name(t));
  }
  out.contact_samples = contacts.ContactSamples();  // 0 without contacts.
  clip.solve.floor_weight = out.own_skeleton ? 0.0 : options.floor_weight;
  clip.solve.floor_joints = TargetFootJoints(out.joint_map);
  clip.solve.floor_heights = FootRestClearances(target_skeleton, clip.solve.floor_joints, target_rest, target.mesh);
  SetLimbGoals(*source.skeleton, motion, target_skeleton, target_rest, out, &clip, &out.notes);
  out.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  status = RetargetClip(*source.skeleton, *source_mesh, motion, target_skeleton, *target.mesh, out.setup, clip,
                        &out.clip, progress);
  if (!status.ok()) return status;

  MeasurePlantSkating(target_skeleton, motion, contacts, contact_targets, &out);
  RetargetQualityInputs quality;
  quality.source = source.skeleton;
  quality.source_motion = &motion;
  quality.target = &target_skeleton;
  quality.result = &out.clip.motion;
  quality.target_mesh = target.mesh;
  quality.target_rest = target_rest;
  quality.source_upright = out.skeleton_only ? &binding.upright_world : nullptr;
  quality.source_upright_positions = out.skeleton_only ? &binding.upright_positions : nullptr;
  quality.target_bind = target_bind;
  quality.target_world_from_bind = setup_options.target_world_from_bind;
  quality.joint_map = &out.joint_map;
  quality.setup = out.own_skeleton ? nullptr : &out.setup;
  quality.height_ratio = out.height_ratio;
  quality.own_skeleton = out.own_skeleton;
  quality.own_scale = own_scale;
  quality.foot_skate_cm_s = out.result_plant_skating_cm_s;
  out.quality = MeasureRetargetQuality(quality);
  const int hips = out.joint_map.target_roles.humanoid ? out.joint_map.target_roles.Find("pelvis")
                                                       : FirstBranchingJoint(target_skeleton);
  status = ApplyRootMotion(target_skeleton, hips, options.root_motion, &out.clip.motion, &out.root_motion);
  if (!status.ok()) return status;
  if (!out.root_motion.note.empty()) out.notes.push_back(out.root_motion.note);
  *result = std::move(out);
  return Status::Ok();
}

// True when the source skeleton has every IK bone under the same parent (by name, or by the
// given joint map's names): its clip drives them itself (the character's own skeleton, a
// clip made for the rig).
bool SourceDrivesIkBones(const Skeleton& source, const Skeleton& target, const FloorIkBones& ik,
                         const std::vector<std::pair<std::string, std::string>>& joint_map) {
  auto source_name = [&](const std::string& target_name) {
    for (const auto& link : joint_map) {
      if (link.second == target_name) return link.first;
    }
    return target_name;
  };
  for (int j : ik.bones) {
    const int s = source.FindJoint(source_name(target.name(j)));
    if (s <= 0 || source.name(source.parent(s)) != source_name(target.name(target.parent(j)))) return false;
  }
  return true;
}

// A result on the solve character re-indexed onto the character (floor_ik_bones.h).
void ResultOnCharacter(const Skeleton& skeleton, const FloorIkBones& ik, const FloorIkSolveCharacter& solve,
                       CharacterRetargetResult* result) {
  const std::vector<int>& to = solve.character_of_solve;
  JointMap& map = result->joint_map;
  for (int& t : map.target_of_source) t = t >= 0 ? to[t] : t;
  std::vector<int> source_of_target(map.source_of_target.size(), -1);
  for (size_t k = 0; k < map.source_of_target.size(); ++k) source_of_target[to[k]] = map.source_of_target[k];
  map.source_of_target = std::move(source_of_target);
  for (auto& role : map.target_roles.roles) role.second = role.second >= 0 ? to[role.second] : role.second;
  for (JointMapRole& role : map.roles) role.target = role.target >= 0 ? to[role.target] : role.target;
  for (int& j : result->setup.position_joints) j = to[j];
  if (result->root_motion.hips >= 0) result->root_motion.hips = to[result->root_motion.hips];
  if (result->root_motion.root_bone >= 0) result->root_motion.root_bone = to[result->root_motion.root_bone];
  result->clip.motion = FloorIkMotionOnCharacter(skeleton, ik, solve, result->clip.motion);
}

Status RetargetOntoCharacter(const RetargetCharacter& source, const Motion& source_motion, Motion* consumed,
                             const RetargetCharacter& target, const CharacterRetargetOptions& options,
                             CharacterRetargetResult* result, const RetargetProgressCallback& progress) {
  Status status = CheckInputs(source, source_motion, target, options);
  if (!status.ok()) return status;
  // IK bones under a floor root follow their chains in the solve (floor_ik_bones.h).
  const Skeleton& skeleton = *target.skeleton;
  const Pose bind = target.bind_pose.rotations.empty() ? RestPose(skeleton) : target.bind_pose;
  const Pose rest = target.rest_pose.rotations.empty() ? bind : target.rest_pose;
  const JointMapSkeleton standing = StandingSkeleton(skeleton, bind, target.mesh, rest);
  const FloorIkBones ik = FindFloorIkBones(skeleton, standing.positions, FindRoles(standing), target.mesh);
  if (ik.empty() || SourceDrivesIkBones(*source.skeleton, skeleton, ik, options.joint_map)) {
    return RetargetOntoSolveCharacter(source, source_motion, consumed, target, options, result, progress);
  }
  FloorIkSolveCharacter solve;
  status = MakeFloorIkSolveCharacter(skeleton, *target.mesh, bind, rest, ik, &solve);
  if (!status.ok()) return status;
  RetargetCharacter solve_target;
  solve_target.skeleton = &solve.skeleton;
  solve_target.mesh = &solve.mesh;
  solve_target.bind_pose = solve.bind_pose;
  solve_target.rest_pose = solve.rest_pose;
  CharacterRetargetOptions solve_options = options;
  if (!options.clip.start_pose.rotations.empty()) {
    solve_options.clip.start_pose = FloorIkPoseOnSolveCharacter(skeleton, ik, solve, options.clip.start_pose);
  }
  for (Pose& pose : solve_options.clip.warm_start.frames) pose = FloorIkPoseOnSolveCharacter(skeleton, ik, solve, pose);
  status = RetargetOntoSolveCharacter(source, source_motion, consumed, solve_target, solve_options, result, progress);
  if (!status.ok()) return status;
  ResultOnCharacter(skeleton, ik, solve, result);
  result->notes.push_back("IK bones under the floor root follow their chains in the solve and carry translation "
                          "keys: " + ik.Describe(skeleton));
  return Status::Ok();
}

}  // namespace

Status RetargetMotionOntoCharacter(const RetargetCharacter& source, const Motion& source_motion,
                                   const RetargetCharacter& target, const CharacterRetargetOptions& options,
                                   CharacterRetargetResult* result, const RetargetProgressCallback& progress) {
  return RetargetOntoCharacter(source, source_motion, nullptr, target, options, result, progress);
}

Status RetargetMotionOntoCharacter(const RetargetCharacter& source, Motion&& source_motion,
                                   const RetargetCharacter& target, const CharacterRetargetOptions& options,
                                   CharacterRetargetResult* result, const RetargetProgressCallback& progress) {
  const Status status = RetargetOntoCharacter(source, source_motion, &source_motion, target, options, result, progress);
  source_motion = Motion();
  return status;
}

}  // namespace mocapsolve
