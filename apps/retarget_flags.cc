#include "apps/retarget_flags.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "apps/config_flags.h"
#include "apps/solver_flags.h"
#include "io/json_reader.h"

DECLARE_double(limit_weight);   // apps/solver_flags.cc: soft joint limits, where the skeleton has them.
// apps/propagate_command.cc: here the source joints to plant (default: names with foot, toe, ankle).
DECLARE_string(foot_joints);

DEFINE_string(joint_map, "", "JSON {\"joints\": {\"<source joint>\": \"<target joint>\"}}: overrides "
              "of the automatic joint map (names; used to bind a skeleton-only source and for the plants).");
DEFINE_bool(plant_feet, true, "Keep the target's feet planted where the source's foot joints are in "
            "contact (an IK term in each frame's solve).");
DEFINE_double(plant_weight, 10.0, "Weight of a planted foot joint (per sigma of position error, as a "
              "position-tracked vertex has 1); 0 = off.");
DEFINE_double(plant_height, 0.03, "Foot contact: source foot joint at most this high above its lowest "
              "point (fraction of the source height).");
DEFINE_double(plant_speed, 0.15, "Foot contact: source foot joint slower than this (source heights/s).");
DEFINE_int32(subsample, 128, "Subsampling ratio #V : #tracked vertices of the source mesh.");
DEFINE_int32(iterations, 10, "Solver iterations per frame.");
DEFINE_double(lambda, 5.0, "DLS damping (thesis eq. 18).");
DEFINE_string(blend_mask, "auto", "auto (hands, feet, toes, head by position; the rest by normals) "
              "or a JSON file {\"position_joints\": [target joint names]}.");
DEFINE_double(mapping_normal_weight, 0.0, "Normals in the mesh mapping's nearest-neighbour distance "
              "(heights per unit normal difference); 0 = positions only (thesis eq. 11).");
DEFINE_bool(transfer_normals, true, "Normal goals: the target vertex's rest normal turned by the "
            "source vertex's skinning (true) or the source's skinned normal itself (false, eq. 16).");
DEFINE_double(normal_weight, 1.0, "Weight of the normal residuals (positions: 1 per sigma).");
DEFINE_double(smoothness, 0.0, "Weight of a pull toward the previous frame (per radian); 0 = off.");
DEFINE_double(contact_height, 0.02, "Foot contact: height above the rest floor, fraction of the "
              "target height (for the foot-skating figures).");
DEFINE_double(ceres_trust_radius, 1.0, "Ceres' initial trust region radius (its default is 1e4; ~1 "
              "converges better within a few iterations on the cross-character cases).");

namespace mocapsolve {
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

// {"joints": {"<source joint>": "<target joint>", ...}}.
Status ReadJointMap(const std::string& path, std::vector<std::pair<std::string, std::string>>* pairs) {
  JsonNode root;
  Status status = ReadJsonFile(path, &root);
  if (!status.ok()) return status;
  const JsonNode* joints = root.Find("joints");
  if (joints == nullptr || !joints->is_object()) {
    return Status::Error(root.Where(path) + ": expected an object with an object \"joints\" "
                         "{\"<source joint>\": \"<target joint>\"}");
  }
  for (const auto& [source, target] : joints->members) {
    if (!target.is_string() || target.string.empty()) {
      return Status::Error(target.Where(path) + ": joints: '" + source + "': expected a target joint name");
    }
    pairs->push_back({source, target.string});
  }
  return Status::Ok();
}

}  // namespace

const char* const kRetargetOptionFlagNames =
    "joint_map,plant_feet,plant_weight,plant_height,plant_speed,foot_joints,subsample,iterations,lambda,"
    "blend_mask,mapping_normal_weight,transfer_normals,normal_weight,smoothness,contact_height,"
    "ceres_trust_radius";

Status RetargetOptionsFromFlags(CharacterRetargetOptions* options_out) {
  CharacterRetargetOptions& options = *options_out;
  RetargetSolveOptions& solve = options.clip.solve;
  const std::string solver_name =
      gflags::GetCommandLineFlagInfoOrDie("solver").is_default ? "dls" : FLAGS_solver;
  if (!ParseRetargetSolverKind(solver_name, &solve.solver)) {
    return Status::Error("--solver: unknown solver '" + FLAGS_solver + "' (dls, dls_generic, ceres)");
  }
  if (FLAGS_subsample < 1) return Status::Error("--subsample: must be >= 1");
  if (FLAGS_iterations < 1 || FLAGS_iterations > 1000) return Status::Error("--iterations: must be in [1, 1000]");
  if (!(FLAGS_contact_height > 0.0)) return Status::Error("--contact_height: must be > 0");
  if (FLAGS_mapping_normal_weight < 0.0) return Status::Error("--mapping_normal_weight: must be >= 0");
  if (!(FLAGS_plant_weight >= 0.0)) return Status::Error("--plant_weight: must be >= 0");
  if (!(FLAGS_plant_height > 0.0) || !(FLAGS_plant_speed > 0.0)) {
    return Status::Error("--plant_height and --plant_speed: must be > 0");
  }
  solve.iterations = FLAGS_iterations;
  solve.lambda = FLAGS_lambda;
  solve.normal_weight = FLAGS_normal_weight;
  solve.smoothness_weight = FLAGS_smoothness;
  solve.limit_weight = FLAGS_limit_weight;
  solve.plant_weight = FLAGS_plant_weight;
  solve.ceres = DefaultRetargetCeresOptions();
  solve.ceres.initial_trust_region_radius = FLAGS_ceres_trust_radius;
  options.clip.contact_height = FLAGS_contact_height;
  options.setup.subsample.ratio = FLAGS_subsample;
  options.setup.mapping_normal_weight = FLAGS_mapping_normal_weight;
  options.setup.transfer_normals = FLAGS_transfer_normals;
  options.plant_feet = FLAGS_plant_feet && FLAGS_plant_weight > 0.0;
  options.contact_height = FLAGS_plant_height;
  options.contact_speed = FLAGS_plant_speed;
  options.foot_joints = SplitCommaList(FLAGS_foot_joints);

  std::string error;
  if (!options.IsValid(&error)) return Status::Error("retarget options: " + error);
  Status status = Status::Ok();
  if (FLAGS_blend_mask != "auto") {
    status = ReadBlendMask(FLAGS_blend_mask, &options.setup.position_joints);
    if (!status.ok()) return status;
  }
  if (!FLAGS_joint_map.empty()) {
    status = ReadJointMap(FLAGS_joint_map, &options.joint_map);
    if (!status.ok()) return status;
  }

  return Status::Ok();
}

}  // namespace mocapsolve
