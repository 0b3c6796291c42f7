// `joint_map` as one function: the automatic joint correspondence between a source (any
// motion or character file) and a target character (problems/retarget/joint_map.h: names,
// then the humanoid roles found by structure, humanoid_roles.h), with a joint map file's
// overrides applied, as the JSON that --joint_map reads back (docs/retarget.md, "Joint
// map"). Also the JSON of a map for retarget's report.
//
// The JSON: {"source", "target": the paths, "confidence": 0..1, "source_skeleton" and
// "target_skeleton": "humanoid (roles: ...)" or "not a humanoid (...)", "roles": {role:
// {"source": joint, "target": joint, "how": name|structure|topology|file|""}}, "joints":
// {source joint: target joint} for every mapped joint}. Roles found on one side only have
// "" for the other side's joint.
#ifndef MOCAPSOLVE_TASKS_JOINT_MAP_TASK_H_
#define MOCAPSOLVE_TASKS_JOINT_MAP_TASK_H_

#include <string>

#include "io/json_writer.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/retarget/joint_map.h"

namespace mocapsolve {

struct JointMapInputs {
  std::string source;            // .glb/.gltf, .bvh, .amc (with skeleton), .fbx.
  std::string target;            // Same kinds.
  std::string skeleton;          // An .amc's .asf.
  std::string source_skin, target_skin;  // glTF skins by name or index ("" = skin 0).
};

struct JointMapConfig {
  std::string joint_map;  // A joint map file whose entries override the automatic map ("" = none).
};

struct JointMapTaskResult {
  Skeleton source, target;
  JointMap map;
  JsonObject json;  // What the command prints (see the header).
};

// Errors: an unreadable input (naming the file), a joint map file naming a joint that does
// not exist (naming it and the side).
Status RunJointMap(const JointMapInputs& inputs, const JointMapConfig& config, JointMapTaskResult* result);

// "roles" of the JSON above.
JsonObject JointMapRolesJson(const JointMap& map, const Skeleton& source, const Skeleton& target);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_JOINT_MAP_TASK_H_
