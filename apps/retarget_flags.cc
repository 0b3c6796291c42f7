#include "apps/retarget_flags.h"

#include "settings/retarget_settings.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "apps/config_flags.h"
#include "apps/option_flags.h"
#include "apps/solver_flags.h"

DECLARE_double(limit_weight);   // apps/solver_flags.cc: soft joint limits, where the skeleton has them.
// apps/propagate_command.cc: here the source joints to plant (default: names with foot, toe, ankle).
DECLARE_string(foot_joints);

namespace {
// The flags' defaults are the settings' (settings/retarget_settings.h): one source.
const mocapsolve::RetargetSettings kDefault;
}  // namespace

DEFINE_string(joint_map, kDefault.joint_map.c_str(), "JSON {\"joints\": {\"<source joint>\": \"<target joint>\"}}: overrides "
              "of the automatic joint map (names; used to bind a skeleton-only source and for the plants).");
DEFINE_bool(plant_feet, kDefault.plant_feet, "Keep the target's feet planted where the source's foot joints are in "
            "contact (an IK term in each frame's solve).");
DEFINE_double(plant_weight, kDefault.plant_weight, "Weight of a planted foot joint (per sigma of position error, as a "
              "position-tracked vertex has 1); 0 = off.");
DEFINE_double(plant_height, kDefault.plant_height, "Foot contact: source foot joint at most this high above its lowest "
              "point (fraction of the source height).");
DEFINE_double(plant_speed, kDefault.plant_speed, "Foot contact: source foot joint slower than this (source heights/s).");
DEFINE_int32(subsample, kDefault.subsample, "Subsampling ratio #V : #tracked vertices of the source mesh.");
DEFINE_int32(iterations, kDefault.iterations, "Solver iterations per frame.");
DEFINE_double(lambda, kDefault.lambda, "DLS damping (thesis eq. 18).");
DEFINE_string(blend_mask, kDefault.blend_mask.c_str(), "auto (hands, feet, toes, head by position; the rest by normals) "
              "or a JSON file {\"position_joints\": [target joint names]}.");
DEFINE_double(mapping_normal_weight, kDefault.mapping_normal_weight, "Normals in the mesh mapping's nearest-neighbour distance "
              "(heights per unit normal difference); 0 = positions only (thesis eq. 11).");
DEFINE_bool(transfer_normals, kDefault.transfer_normals, "Normal goals: the target vertex's rest normal turned by the "
            "source vertex's skinning (true) or the source's skinned normal itself (false, eq. 16).");
DEFINE_double(normal_weight, kDefault.normal_weight, "Weight of the normal residuals (positions: 1 per sigma).");
DEFINE_double(smoothness, kDefault.smoothness, "Weight of a pull toward the previous frame (per radian); 0 = off.");
DEFINE_double(contact_height, kDefault.contact_height, "Foot contact: height above the rest floor, fraction of the "
              "target height (for the foot-skating figures).");
DEFINE_double(ceres_trust_radius, kDefault.ceres_trust_radius, "Ceres' initial trust region radius (its default is 1e4; ~1 "
              "converges better within a few iterations on the cross-character cases).");
DEFINE_bool(animation_only, false, "Write each retargeted .glb/.gltf as an animation-only glTF: the character's "
            "skeleton nodes (same names and rest transforms), its skin and the new animation, without meshes, "
            "materials or images; Blender (scripts/apply_animation_gltf.py) and three.js play it on the "
            "character file they already have.");

namespace mocapsolve {

Status RetargetOptionsFromFlags(CharacterRetargetOptions* options) {
  RetargetSettings s;
  // --solver and --limit_weight: retarget's own (RetargetSolverOptions), or in pipeline the
  // marker solver's of the same names (dls by default there too).
  Status status = ReadOptionFlags(RetargetSolverOptions(), &s);
  if (!status.ok()) return status;
  s.joint_map = FLAGS_joint_map;
  s.plant_feet = FLAGS_plant_feet;
  s.plant_weight = FLAGS_plant_weight;
  s.plant_height = FLAGS_plant_height;
  s.plant_speed = FLAGS_plant_speed;
  s.foot_joints = FLAGS_foot_joints;
  s.subsample = FLAGS_subsample;
  s.iterations = FLAGS_iterations;
  s.lambda = FLAGS_lambda;
  s.blend_mask = FLAGS_blend_mask;
  s.mapping_normal_weight = FLAGS_mapping_normal_weight;
  s.transfer_normals = FLAGS_transfer_normals;
  s.normal_weight = FLAGS_normal_weight;
  s.smoothness = FLAGS_smoothness;
  s.contact_height = FLAGS_contact_height;
  s.ceres_trust_radius = FLAGS_ceres_trust_radius;
  return RetargetOptionsFromSettings(s, options);
}

}  // namespace mocapsolve
