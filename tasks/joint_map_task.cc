#include "tasks/joint_map_task.h"

#include <utility>
#include <vector>

#include "io/gltf_reader.h"
#include "io/motion_file.h"
#include "settings/retarget_settings.h"

namespace mocapsolve {
namespace {

// A side as the map sees it: a glTF's skin (bind pose, node rest pose, weights) or any
// motion file's skeleton (rest pose).
Status ReadSide(const std::string& path, const std::string& skeleton_path, const std::string& skin,
                Skeleton* skeleton, JointMapSkeleton* standing) {
  const std::string extension = FileExtension(path);
  if (extension == ".glb" || extension == ".gltf") {
    GltfReadOptions options;
    options.skin = skin;
    GltfCharacter character;
    Status status = ReadGltfCharacter(path, options, &character);
    if (!status.ok()) return status;
    *skeleton = character.skeleton;
    const Pose bind = character.bind_pose.rotations.empty() ? RestPose(*skeleton) : character.bind_pose;
    *standing = StandingSkeleton(*skeleton, bind, &character.mesh, character.rest_pose);
    standing->skeleton = skeleton;
    return Status::Ok();
  }
  if (!skin.empty()) return Status::Error(path + ": a skin applies to a glTF only");
  MotionFileOptions options;
  options.skeleton_path = skeleton_path;
  Motion motion;
  Status status = ReadMotionFile(path, options, skeleton, &motion);
  if (!status.ok()) return status;
  *standing = StandingSkeleton(*skeleton, Pose(), nullptr, motion.frames.empty() ? Pose() : motion.frames[0]);
  return Status::Ok();
}

}  // namespace

JsonObject JointMapRolesJson(const JointMap& map, const Skeleton& source, const Skeleton& target) {
  JsonObject roles;
  for (const JointMapRole& role : map.roles) {
    JsonObject entry;
    entry.Add("source", role.source >= 0 ? source.name(role.source) : std::string())
        .Add("target", role.target >= 0 ? target.name(role.target) : std::string())
        .Add("how", role.how);
    roles.Add(role.role, entry);
  }
  return roles;
}

Status RunJointMap(const JointMapInputs& inputs, const JointMapConfig& config, JointMapTaskResult* result) {
  JointMapSkeleton source, target;
  Status status = ReadSide(inputs.source, inputs.skeleton, inputs.source_skin, &result->source, &source);
  if (status.ok()) status = ReadSide(inputs.target, "", inputs.target_skin, &result->target, &target);
  if (!status.ok()) return status;
  std::vector<std::pair<std::string, std::string>> overrides;
  if (!config.joint_map.empty()) {
    status = ReadJointMapFile(config.joint_map, &overrides);
    if (!status.ok()) return status;
  }
  status = BuildJointMap(source, target, overrides, &result->map);
  if (!status.ok()) return Status::Error(inputs.source + " -> " + inputs.target + ": " + status.message());
  JsonObject joints;
  for (int j = 0; j < result->source.num_joints(); ++j) {
    const int t = result->map.target_of_source[j];
    if (t >= 0) joints.Add(result->source.name(j), result->target.name(t));
  }
  result->json = JsonObject()
                     .Add("source", inputs.source)
                     .Add("target", inputs.target)
                     .Add("confidence", result->map.confidence)
                     .Add("source_skeleton", result->map.Found(true))
                     .Add("target_skeleton", result->map.Found(false))
                     .Add("roles", JointMapRolesJson(result->map, result->source, result->target))
                     .Add("joints", joints);
  return Status::Ok();
}

}  // namespace mocapsolve
