#include "settings/retarget_settings.h"

#include <string>
#include <utility>
#include <vector>

#include "io/comma_list.h"
#include "io/json_reader.h"

namespace mocapsolve {

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

Status RetargetOptionsFromSettings(const RetargetSettings& settings, CharacterRetargetOptions* options_out) {
  Status checked = RetargetSolverOptions().Validate(settings);
  if (!checked.ok()) return checked;
  CharacterRetargetOptions& options = *options_out;
  RetargetSolveOptions& solve = options.clip.solve;
  if (!ParseRetargetSolverKind(settings.solver, &solve.solver)) {
    return Status::Error("--solver: unknown solver '" + settings.solver + "' (dls, dls_generic, ceres)");
  }
  if (settings.subsample < 1) return Status::Error("--subsample: must be >= 1");
  if (settings.iterations < 1 || settings.iterations > 1000) return Status::Error("--iterations: must be in [1, 1000]");
  if (!(settings.contact_height > 0.0)) return Status::Error("--contact_height: must be > 0");
  if (settings.mapping_normal_weight < 0.0) return Status::Error("--mapping_normal_weight: must be >= 0");
  if (!(settings.plant_weight >= 0.0)) return Status::Error("--plant_weight: must be >= 0");
  if (!(settings.plant_height > 0.0) || !(settings.plant_speed > 0.0)) {
    return Status::Error("--plant_height and --plant_speed: must be > 0");
  }
  solve.iterations = settings.iterations;
  solve.lambda = settings.lambda;
  solve.normal_weight = settings.normal_weight;
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
  options.contact_height = settings.plant_height;
  options.contact_speed = settings.plant_speed;
  options.foot_joints = SplitCommaList(settings.foot_joints);

  std::string error;
  if (!options.IsValid(&error)) return Status::Error("retarget options: " + error);
  Status status = Status::Ok();
  if (settings.blend_mask != "auto") {
    status = ReadBlendMask(settings.blend_mask, &options.setup.position_joints);
    if (!status.ok()) return status;
  }
  if (!settings.joint_map.empty()) {
    status = ReadJointMap(settings.joint_map, &options.joint_map);
    if (!status.ok()) return status;
  }

  return Status::Ok();
}

}  // namespace mocapsolve
