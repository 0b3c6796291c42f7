// mocapsolve joint_map --source=A --target=B: the automatic joint map between two
// skeletons (names, then humanoid roles by structure; tasks/joint_map_task.h) as the JSON
// that --joint_map reads, for editing.
#include <cstdio>
#include <string>
#include <vector>

#include "apps/command.h"
#include "settings/retarget_run_settings.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "io/atomic_file.h"
#include "settings/retarget_settings.h"
#include "tasks/joint_map_task.h"


namespace mocapsolve {
namespace {

Status JointMapMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().source.empty() || Files().target.empty()) return Status::Error("--source and --target are required");
  RetargetSettings settings;
  ReadOptionFlags(RetargetSettingOptions().Only("joint_map"), &settings);
  if (!Files().out.empty()) {
    for (const std::string& in : {Files().source, Files().target, Files().skeleton, settings.joint_map}) {
      if (in.empty()) continue;
      Status status = CheckNotAnInput(Files().out, in);
      if (!status.ok()) return status;
    }
  }
  JointMapInputs inputs;
  inputs.source = Files().source;
  inputs.target = Files().target;
  inputs.skeleton = Files().skeleton;
  RetargetRunSettings run;
  ReadOptionFlags(RetargetRunSettingOptions(), &run);
  inputs.source_skin = run.source_skin;
  inputs.target_skin = run.target_skin;
  JointMapConfig config;
  config.joint_map = settings.joint_map;
  JointMapTaskResult result;
  Status status = RunJointMap(inputs, config, &result);
  if (!status.ok()) return status;
  const std::string text = result.json.ToString() + "\n";
  if (Files().out.empty() || Files().out == "-") {
    std::fputs(text.c_str(), stdout);
    return Status::Ok();
  }
  return WriteFileAtomically(Files().out, text);
}

}  // namespace

extern const Command kJointMapCommand = {
    "joint_map", "print the automatic joint map between two skeletons (JSON for --joint_map)",
    "mocapsolve joint_map --source=SRC.glb|.bvh|.amc|.fbx [--skeleton=X.asf] --target=TGT.glb "
    "[--joint_map=EDITED.json] [--out=map.json]\n\n"
    "Maps the source's joints to the target's as retarget does: equal or synonymous names, then\n"
    "the humanoid roles (pelvis, spine, chest, neck, head; per side clavicle, upper arm, forearm,\n"
    "hand, thigh, shin, foot, toes) found from each skeleton's structure and rest pose, where\n"
    "names leave a role unmapped or disagree; two non-humanoids with the same hierarchy map joint\n"
    "by joint. Prints (or writes to --out) the map as JSON: each role's source and target joint\n"
    "and how it was decided (name, structure, topology, file), a confidence, and every joint pair.\n"
    "Edit it and pass it to retarget or pipeline as --joint_map; given here, it is applied first.",
    __FILE__, JointMapMain,
    {SharedOptions("source,target,skeleton,out"),
     RetargetRunSettingOptions().Only("source_skin,target_skin").options(),
     RetargetSettingOptions().Only("joint_map").options()}};

}  // namespace mocapsolve
