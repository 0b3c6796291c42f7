#include "settings/retarget_settings.h"

#include <string>
#include <utility>
#include <vector>

#include "io/comma_list.h"
#include "io/json_reader.h"

namespace mocapsolve {

const OptionGroup<RetargetSettings>& RetargetSettingOptions() {
  using S = RetargetSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::joint_map, "joint_map",
           "JSON {\"joints\": {\"<source joint>\": \"<target joint>\"}, \"roles\": {\"<role>\": "
           "{\"source\": ..., \"target\": ...}}} (what `mocapsolve joint_map` prints): overrides of the "
           "automatic joint map (names, then humanoid roles by structure; used to bind a skeleton-only "
           "source and for the plants).")
      .Add(&S::plant_feet, "plant_feet",
           "Keep the target's feet planted where the source's foot joints are in "
           "contact (an IK term in each frame's solve).")
      .Add(&S::plant_weight, "plant_weight", "",
           "Weight of a planted foot joint (per sigma of position error, as a "
           "position-tracked vertex has 1); 0 = off.")
      .Add(&S::floor_weight, "floor_weight", "",
           "Weight that keeps the target's feet and toes out of the floor: each foot and toes joint at or above "
           "its rest height over the character's sole (per sigma of depth, as a position-tracked vertex has 1; "
           "plant anchors are lifted to it too); 0 = off.")
      .Add(&S::plant_height, "plant_height", "source heights",
           "Foot contact: source foot joint at most this high above its lowest "
           "point (fraction of the source height).")
      .Add(&S::plant_speed, "plant_speed", "source heights/s",
           "Foot contact: source foot joint slower than this (source heights/s).")
      .Add(&S::root_motion, "root_motion",
           "Where the clip's horizontal motion goes: keep (as solved), root_bone (carried by the target's root "
           "bone at the floor above the hips, as game engines' root motion wants: the hips' ground projection "
           "and heading, smoothed; every other joint stays where it was) or in_place (removed: the clip "
           "walks on the spot, heading kept; a root bone stays at rest).",
           {"keep", "root_bone", "in_place"})
      .Add(&S::root_smoothing, "root_smoothing", "s",
           "Standard deviation of the Gaussian that smooths the root track (ground projection and heading of "
           "the hips) for root_bone and in_place; 0 = the hips' own path.", 0)
      .Add(&S::stride, "stride",
           "Stride length of a skeleton-only source on the target: height (the source's path times the height "
           "ratio) or legs (times the leg-length ratio: a character whose legs are a smaller share of its "
           "height takes shorter steps, so planted feet slide less).",
           {"height", "legs"})
      .Add(&S::subsample, "subsample", "vertices per sample",
           "Subsampling ratio #V : #tracked vertices of the source mesh.")
      .Add(&S::iterations, "iterations", "iterations",
           "Solver iterations per frame (Ceres: its cap; the thesis' DLS: 10 at damping 5, which these "
           "defaults match in final cost).")
      .Add(&S::lambda, "lambda", "",
           "DLS damping (thesis eq. 18).")
      .Add(&S::blend_mask, "blend_mask",
           "auto (hands, feet, toes, head by position; the rest by normals) "
           "or a JSON file {\"position_joints\": [target joint names]}.")
      .Add(&S::mapping_normal_weight, "mapping_normal_weight", "heights per unit normal",
           "Normals in the mesh mapping's nearest-neighbour distance "
           "(heights per unit normal difference); 0 = positions only (thesis eq. 11).")
      .Add(&S::transfer_normals, "transfer_normals",
           "Normal goals: the target vertex's rest normal turned by the "
           "source vertex's skinning (true) or the source's skinned normal itself (false, eq. 16).")
      .Add(&S::normal_weight, "normal_weight", "",
           "Weight of the normal residuals (positions: 1 per sigma).")
      .Add(&S::limb_direction_weight, "limb_direction_weight", "1/rad",
           "Weight of the eight limbs (upper arms, forearms, thighs, shins) pointing as the source's do "
           "(per unit of direction difference, ~ per radian; normals have 1), against the vertex tracking: "
           "higher follows the source's limb directions more and its end-effector positions less "
           "(docs/retargeting.md, \"Limb directions\"); 0 = off.", 0)
      .Add(&S::smoothness, "smoothness", "1/rad",
           "Weight of a pull toward the previous frame (per radian); 0 = off.")
      .Add(&S::contact_height, "contact_height", "target heights",
           "Foot contact: height above the rest floor, fraction of the "
           "target height (for the foot-skating figures).")
      .Add(&S::ceres_trust_radius, "ceres_trust_radius", "",
           "Ceres' initial trust region radius (its default is 1e4; ~1 "
           "converges better within a few iterations on the cross-character cases).");
  return *group;
}

const OptionGroup<RetargetSettings>& RetargetSolverOptions() {
  using S = RetargetSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::solver, "solver",
           "dls | dls_generic | ceres: who minimizes each frame's vertex residuals (dls: the lean kernel, eq. 18).",
           {"dls", "dls_generic", "ceres"})
      .Add(&S::limit_weight, "limit_weight", "1/rad",
           "Soft joint limits of the source skeleton's joints as they map to the target (ASF 'limits'): the "
           "weight of 1 radian beyond a limit against vertex residuals of 1 per sigma; 0 = off.", 0);
  return *group;
}
namespace {

Status ReadBlendMask(const std::string& path, std::vector<std::string>* joints) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  const JsonNode* list = root.Find("position_joints");
  if (list == nullptr || !list->is_array()) {
    return Status::Error(root.Where(path) + ": expected an object with an array \"position_joints\"");
  }
  for (const JsonNode& item : list->items) {
    if (!item.is_string() || item.string.empty()) {
      return Status::Error(item.Where(path) + ": position_joints: expected a joint name");
    }
    joints->push_back(item.string);
  }
  if (joints->empty()) return Status::Error(list->Where(path) + ": position_joints is empty");
  return Status::Ok();
}

}  // namespace

Status ReadJointMapFile(const std::string& path, std::vector<std::pair<std::string, std::string>>* pairs) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  const JsonNode* joints = root.Find("joints");
  const JsonNode* roles = root.Find("roles");
  if ((joints == nullptr || !joints->is_object()) && (roles == nullptr || !roles->is_object())) {
    return Status::Error(root.Where(path) + ": expected an object with an object \"joints\" "
                         "{\"<source joint>\": \"<target joint>\"} or \"roles\" "
                         "{\"<role>\": {\"source\": \"<joint>\", \"target\": \"<joint>\"}}");
  }
  if (roles != nullptr && roles->is_object()) {
    for (const auto& [role, entry] : roles->members) {
      const JsonNode* source = entry.is_object() ? entry.Find("source") : nullptr;
      const JsonNode* target = entry.is_object() ? entry.Find("target") : nullptr;
      if (source == nullptr || target == nullptr || !source->is_string() || !target->is_string()) {
        return Status::Error(entry.Where(path) + ": roles: '" + role +
                             "': expected {\"source\": \"<joint>\", \"target\": \"<joint>\"}");
      }
      // A role found on one side only ("" on the other) is no override.
      if (!source->string.empty() && !target->string.empty()) pairs->push_back({source->string, target->string});
    }
  }
  if (joints != nullptr && joints->is_object()) {
    for (const auto& [source, target] : joints->members) {
      if (!target.is_string() || target.string.empty()) {
        return Status::Error(target.Where(path) + ": joints: '" + source + "': expected a target joint name");
      }
      pairs->push_back({source, target.string});
    }
  }
  return Status::Ok();
}

Status RetargetOptionsFromSettings(const RetargetSettings& settings, CharacterRetargetOptions* options_out) {
  Status checked = RetargetSolverOptions().Validate(settings);
  if (checked.ok()) checked = RetargetSettingOptions().Validate(settings);
  if (!checked.ok()) return checked;
  CharacterRetargetOptions& options = *options_out;
  RetargetSolveOptions& solve = options.clip.solve;
  if (!ParseSolverKind(settings.solver, &solve.solver)) {
    return Status::Error("--solver: unknown solver '" + settings.solver + "' (dls, dls_generic, ceres)");
  }
  if (settings.subsample < 1) return Status::Error("--subsample: must be >= 1");
  if (settings.iterations < 1 || settings.iterations > 1000) return Status::Error("--iterations: must be in [1, 1000]");
  if (!(settings.contact_height > 0.0)) return Status::Error("--contact_height: must be > 0");
  if (settings.mapping_normal_weight < 0.0) return Status::Error("--mapping_normal_weight: must be >= 0");
  if (!(settings.plant_weight >= 0.0)) return Status::Error("--plant_weight: must be >= 0");
  if (!(settings.floor_weight >= 0.0)) return Status::Error("--floor_weight: must be >= 0");
  if (!(settings.plant_height > 0.0) || !(settings.plant_speed > 0.0)) {
    return Status::Error("--plant_height and --plant_speed: must be > 0");
  }
  solve.iterations = settings.iterations;
  solve.lambda = settings.lambda;
  solve.normal_weight = settings.normal_weight;
  solve.limb_direction_weight = settings.limb_direction_weight;
  solve.smoothness_weight = settings.smoothness;
  solve.limit_weight = settings.limit_weight;
  solve.plant_weight = settings.plant_weight;
  solve.ceres = DefaultRetargetCeresOptions();
  solve.ceres.initial_trust_region_radius = settings.ceres_trust_radius;
  options.clip.contact_height = settings.contact_height;
  options.setup.subsample.ratio = settings.subsample;
  options.setup.mapping_normal_weight = settings.mapping_normal_weight;
  options.setup.transfer_normals = settings.transfer_normals;
  options.plant_feet = settings.plant_feet && settings.plant_weight > 0.0;
  options.floor_weight = settings.floor_weight;
  options.contact_height = settings.plant_height;
  options.contact_speed = settings.plant_speed;
  options.foot_joints = SplitCommaList(settings.foot_joints);
  if (!ParseRootMotionMode(settings.root_motion, &options.root_motion.mode)) {
    return Status::Error("--root_motion: unknown mode '" + settings.root_motion + "' (keep, root_bone, in_place)");
  }
  options.root_motion.smoothing_seconds = settings.root_smoothing;
  options.stride_to_legs = settings.stride == "legs";

  std::string error;
  if (!options.IsValid(&error)) return Status::Error("retarget options: " + error);
  Status status = Status::Ok();
  if (settings.blend_mask != "auto") {
    status = ReadBlendMask(settings.blend_mask, &options.setup.position_joints);
    if (!status.ok()) return status;
  }
  if (!settings.joint_map.empty()) {
    status = ReadJointMapFile(settings.joint_map, &options.joint_map);
    if (!status.ok()) return status;
  }

  return Status::Ok();
}

}  // namespace mocapsolve
