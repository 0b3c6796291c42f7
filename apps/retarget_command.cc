// mocapsolve retarget: a source character's glTF animation onto a target character by
// their meshes (thesis chapter 4; problems/retarget/).
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/delivery_flags.h"
#include "apps/progress.h"
#include "apps/retarget_flags.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "settings/foot_joint_settings.h"
#include "settings/frame_limit_settings.h"
#include "settings/retarget_run_settings.h"
#include "settings/view_page_settings.h"
#include "io/bvh_writer.h"
#include "io/gltf_reader.h"
#include "io/gltf_writer.h"
#include "io/motion_file.h"
#include "tasks/retarget_task.h"

namespace mocapsolve {
namespace {

bool HasExtension(const std::string& path, const std::string& extension) {
  return path.size() > extension.size() &&
         path.compare(path.size() - extension.size(), extension.size(), extension) == 0;
}

Status RetargetMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().source.empty() || Files().target.empty()) return Status::Error("--source and --target are required");
  if (Files().out.empty() && Files().out_bvh.empty()) return Status::Error("--out or --out_bvh is required");
  const std::string joint_map = RetargetSettingsFromFlags().joint_map;
  RetargetRunSettings run;
  ReadOptionFlags(RetargetRunSettingOptions(), &run);
  FrameLimitSettings limit;
  ReadOptionFlags(FrameLimitOption(), &limit);
  Status status = CheckOutputsApart({Files().out, Files().out_bvh, Files().report},
                                    {Files().source, Files().target, Files().skeleton, joint_map});
  if (!status.ok()) return status;
  const bool out_bvh = IsTextOutputPath(Files().out, ".bvh");
  if (!Files().out.empty() && !out_bvh && !HasExtension(Files().out, ".glb") && !HasExtension(Files().out, ".gltf") &&
      !HasExtension(Files().out, ".fbx")) {
    return Status::Error("--out: " + Files().out + ": expected .glb, .gltf, .fbx or .bvh");
  }
  if (run.animation_only && (Files().out.empty() || out_bvh)) {
    return Status::Error("--animation_only: applies to a .glb/.gltf/.fbx --out");
  }
  status = CheckViewFlag({Files().source, Files().target, Files().skeleton, joint_map});
  if (!status.ok()) return status;
  RetargetInputs task_inputs;
  task_inputs.source = Files().source;
  task_inputs.target = Files().target;
  task_inputs.skeleton = Files().skeleton;
  task_inputs.source_animation = run.source_animation;
  task_inputs.source_skin = run.source_skin;
  task_inputs.target_skin = run.target_skin;
  task_inputs.source_mesh = run.source_mesh;
  task_inputs.frame_rate = run.frame_rate;
  task_inputs.amc_fps = FileReading().amc_fps;
  task_inputs.max_frames = limit.max_frames;
  task_inputs.loop = run.loop;
  RetargetConfig config;
  config.retarget = RetargetSettingsFromFlags();
  status = ClipDeliveryFromFlags(&config.delivery);
  if (!status.ok()) return status;
  config.stage_times = run.stage_times;
  std::unique_ptr<Progress> progress;
  SetStage("inputs");
  RetargetTaskResult task;
  status = RunRetarget(task_inputs, config, [&](int done, int total) {
    SetStage("retarget");
    if (!progress) progress = std::make_unique<Progress>("retarget", total, Console().quiet);
    progress->Update(done);
  }, &task);
  if (!status.ok()) return status;
  for (const std::string& note : task.retarget.notes) {
    if (!Console().quiet) std::fprintf(stderr, "note: %s\n", note.c_str());
  }
  const std::string name = RetargetAnimationName(task_inputs, run.animation_name);
  SetStage("writing");
  if (!Files().out.empty()) {
    status = WriteRetargeted(Files().out, task, name, run.animation_only, config.delivery.fbx_key_tolerance_mm);
    if (!status.ok()) return status;
  }
  // --view: the source's skeleton beside the target character playing the result.
  status = WriteViewFlag([&](ViewScene* scene) { return MakeRetargetViewScene(task_inputs, task, name, scene); });
  if (!status.ok()) return status;
  if (!Files().out_bvh.empty()) {
    status = WriteBvh(Files().out_bvh, task.target.skeleton, task.delivered);
    if (!status.ok()) return status;
  }
  if (!Console().quiet) std::fputs(RetargetSummary(task_inputs, config, task).c_str(), stderr);
  JsonObject report;
  report.Add("command", "retarget").Merge(task.report).Add("animation_only", run.animation_only);
  return WriteReport(report);
}

}  // namespace

extern const Command kRetargetCommand = {
    "retarget", "transfer a motion (glTF, BVH, AMC, FBX) onto a glTF character by meshes (thesis ch. 4)",
    "mocapsolve retarget --source=SRC.glb|.bvh|.amc|.fbx [--skeleton=X.asf] [--source_animation=NAME] --target=TGT.glb "
    "--out=OUT.glb|.gltf|.fbx|.bvh [--animation_only] [--out_bvh=OUT.bvh] [--animation_name=NAME] [--solver=dls|dls_generic|ceres] [--subsample=128] "
    "[--iterations=10] [--lambda=5] [--blend_mask=auto|FILE.json] [--report=r.json] [--view=PAGE.html]\n\n"
    "Subsamples the source mesh (farthest points, normal check, >= 3 per joint), maps the samples\n"
    "to the nearest target vertices in a height-normalized rest frame, and solves each frame's\n"
    "target pose (root translation and joint rotations) so that the target vertices track the\n"
    "source's: hands, feet and head by position, the rest by normals. The skeletons may differ.\n"
    "A skeleton-only source (BVH, AMC, FBX; or --source_mesh=false) gets the target's mesh bound\n"
    "to its skeleton after aligning the rest poses (joints mapped by name, --joint_map overrides).\n"
    "Feet are planted where the source's foot joints are in contact (--plant_feet).\n"
    "A .glb/.gltf --out is the target file with the result added as a new animation; with\n"
    "--animation_only just the target's skeleton, skin and that animation (no meshes), to play\n"
    "on the target file an application already has (Blender: scripts/apply_animation_gltf.py).\n"
    "A .fbx --out is binary FBX 7.4: the target's skeleton, skinned mesh (not with\n"
    "--animation_only) and the result as its take.\n"
    "--frames=A:B or --seconds=A:B cut, --out_fps=R resamples the written result (--out, --out_bvh).\n"
    "--solver: dls (the default here: the lean DLS kernel, eq. 18), dls_generic\n"
    "(solvers/dls_solver.h on the same residual blocks) or ceres (Levenberg-Marquardt).",
    __FILE__, RetargetMain,
    {SharedOptions("source,target,out,out_bvh,report,skeleton,amc_fps"),
     RetargetSolverOptions().options(), RetargetSettingOptions().options(), RetargetRunSettingOptions().options(),
     FootJointOption().options(), FrameLimitOption().options(), ViewPageOption().options(),
     DeliverySettingOptions().Without("formats").options()}};

}  // namespace mocapsolve
