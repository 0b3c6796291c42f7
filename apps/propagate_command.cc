// mocapsolve propagate --motion=IN.bvh --frame=I --edit=EDIT.json|--ik_target=JOINT:x,y,z
// [--method=green|harmonic|spline] [--keep_contacts] --out=OUT.bvh: an edit at one or more
// frames propagated through a clip (Dean, Lewis & Chalmers 2018, eqs. 4-5), with the
// Green's-function, harmonic or spline falloff, optionally keeping planted feet in place.
// problems/edit_propagation/.
// The work is tasks/propagate_task.h's RunPropagate; here the flags, the console and the files.
// --frame is distance's flag (apps/distance_command.cc); --method blend's (apps/blend_command.cc),
// read here with its own default (green); the other options are declared in settings/.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "apps/command.h"
#include "settings/edit_settings.h"
#include "settings/foot_joint_settings.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "apps/progress.h"
#include "apps/solver_flags.h"
#include "apps/view_flags.h"
#include "settings/view_page_settings.h"
#include "settings/method_settings.h"
#include "io/atomic_file.h"
#include "io/bvh_writer.h"
#include "io/motion_file.h"
#include "tasks/propagate_task.h"


// apps/distance_command.cc; here required with --ik_target, optional with --edit (then it
// must match a one-edit file's "frame").
namespace mocapsolve {
namespace {

Status PropagateMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().motion.empty() || Files().out.empty()) return Status::Error("--motion and --out are required");
  EditSettings edit;
  ReadOptionFlags(EditSettingOptions(), &edit);
  if (Files().edit.empty() == edit.ik_target.empty()) {
    return Status::Error("give exactly one of --edit=EDIT.json and --ik_target=JOINT:x,y,z");
  }
  if (!IsTextOutputPath(Files().out, ".bvh")) return Status::Error(Files().out + ": expected a .bvh");
  Status status = CheckNotAnInput(Files().out, Files().motion);
  if (status.ok() && !Files().edit.empty()) status = CheckNotAnInput(Files().out, Files().edit);
  if (status.ok()) status = CheckViewFlag({Files().motion, Files().edit});
  if (!status.ok()) return status;
  PropagateConfig config;
  config.edit = Files().edit;
  config.ik_target = edit.ik_target;
  config.frame = edit.frame;
  MethodSetting method;
  ReadOptionFlags(PropagateMethodOption(), &method);
  config.method = method.method;
  FootJointSettings feet;
  ReadOptionFlags(FootJointOption(), &feet);
  config.foot_joints = feet.foot_joints;
  ReadOptionFlags(PropagateSettingOptions(), &config.propagate);
  ReadOptionFlags(FalloffSettingOptions(), &config.falloff);
  ReadOptionFlags(MemoryOption(), &config.memory);
  config.solver = SolverSettingsFromFlags();

  Skeleton skeleton;
  Motion motion;
  SetStage("inputs");
  status = LoadMotion(Files().motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(Files().motion, motion);
  if (!status.ok()) return status;
  std::unique_ptr<Progress> progress;
  SetStage("propagate");
  PropagateResult result;
  status = RunPropagate(skeleton, motion, config, [&](int done, int total) {
    if (!progress) progress = std::make_unique<Progress>("propagate: contact re-solve", total, Console().quiet);
    progress->Update(done);
  }, &result);
  if (!status.ok()) return status;
  std::fputs(PropagateSummary(config, result).c_str(), stdout);

  SetStage("writing");
  status = WriteBvh(Files().out, skeleton, result.propagated);
  if (!status.ok()) return status;
  if (!Files().weights_csv.empty()) {
    status = WriteFileAtomically(Files().weights_csv, FalloffWeightsCsv(result));
    if (!status.ok()) return status;
  }
  // --view: the propagated clip over the original (ghosted), and each edit's falloff.
  status = WriteViewFlag(
      [&](ViewScene* scene) { return MakePropagateViewScene(Files().motion, skeleton, motion, result, scene); });
  if (!status.ok()) return status;
  std::printf("wrote %s: %d frames, %zu edit(s) at frame %d%s, %s falloff over %d:%d\n", Files().out.c_str(),
              motion.num_frames(), result.frames.size(), result.frames[0], result.frames.size() > 1 ? " ..." : "",
              config.method.c_str(), result.region_begin, result.region_end);
  JsonObject report;
  report.Add("motion", Files().motion).Add("out", Files().out).Merge(result.report);
  return WriteReport(report);
}

}  // namespace

extern const Command kPropagateCommand = {
    "propagate", "propagate a pose edit through a clip (Green's function, harmonic or spline falloff)",
    "mocapsolve propagate --motion=IN.bvh --frame=I --edit=EDIT.json|--ik_target=JOINT:x,y,z\n"
    "    [--method=green|harmonic|spline] [--sigma=S] [--region=a:b] [--keep_contacts]\n"
    "    --out=OUT.bvh [--weights_csv=w.csv] [--report=r.json] [--view=PAGE.html]\n\n"
    "Applies the edit of frame I (an edit file's rotation offsets and root translation offset,\n"
    "or an IK solve moving a joint to a point) to every frame f of the region as\n"
    "p'_f = exp(log p_f + w(f) delta) per joint (Dean, Lewis & Chalmers 2018, eqs. 4-5), with\n"
    "w the falloff: green (row of the pose-space Green's function, normalized), harmonic (the\n"
    "harmonic function on the kNN pose graph, 1 at the edit, 0 at other edits and at a ground\n"
    "node (--harmonic_ground) and at the ends of --region; Zhu et al. 2003) or spline (a cubic\n"
    "bump of half-width --spline_width frames).\n"
    "Reports the largest drift of feet planted in the source; --keep_contacts re-solves those\n"
    "frames so the feet stay put.",
    __FILE__, PropagateMain,
    {SharedOptions("motion,edit,out,weights_csv,report,skeleton,skeleton_units,amc_fps,animation,sample_fps"),
     // The IK edit's solve and the harmonic falloff's sparse solve.
     SolverOptions().Only("solver,prior_weight,max_iterations,marker_weight,dls_lambda,dls_damping,sparse_library").options(),
     FalloffSettingOptions().Only("sigma,sigma_scale,eigenpairs,region,knn,falloff_kernel,feature_joints,joint_weights,"
                                  "temporal_weight").options(),
     EditSettingOptions().options(), FootJointOption().options(), PropagateSettingOptions().options(),
     PropagateMethodOption().options(), ViewPageOption().options(), MemoryOption().options()}};

}  // namespace mocapsolve
