// mocapsolve blend --a=A.bvh --b=B.bvh --transition=S:E [--method=multires|weighted]
// --out=OUT.bvh: a transition from A to B (Huang, Boulic & Thalmann, section 3).
// signal/motion_blend.h.
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/pyramid_flags.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "io/bvh_writer.h"
#include "io/motion_file.h"
#include "settings/blend_settings.h"
#include "settings/method_settings.h"
#include "tasks/blend_task.h"


namespace mocapsolve {
namespace {

Status BlendMain(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  BlendSettings settings;
  ReadOptionFlags(BlendSettingOptions(), &settings);
  if (Files().a.empty() || Files().b.empty() || Files().out.empty() || settings.transition.empty()) {
    return Status::Error("--a, --b, --transition and --out are required");
  }
  if (!IsTextOutputPath(Files().out, ".bvh")) return Status::Error(Files().out + ": expected a .bvh");
  Status status = CheckOutputsApart({Files().out}, {Files().a, Files().b});
  if (!status.ok()) return status;
  MethodSetting method;
  ReadOptionFlags(BlendMethodOption(), &method);
  PyramidOptions pyramid;
  status = PyramidOptionsFromFlags(settings.blend_levels, &pyramid);
  if (!status.ok()) return status;

  Skeleton skeleton_a, skeleton_b;
  Motion a, b;
  status = LoadMotion(Files().a, &skeleton_a, &a);
  if (status.ok()) status = RequireFrames(Files().a, a);
  if (status.ok()) status = LoadMotion(Files().b, &skeleton_b, &b);
  if (status.ok()) status = RequireFrames(Files().b, b);
  if (!status.ok()) return status;
  BlendTaskResult result;
  status = RunBlend({&skeleton_a, &a, &skeleton_b, &b, Files().a, Files().b}, method.method, settings, pyramid, &result);
  if (!status.ok()) return status;
  status = WriteBvh(Files().out, skeleton_a, result.blended);
  if (!status.ok()) return status;
  std::printf("wrote %s: %s", Files().out.c_str(), result.summary.c_str());
  JsonObject report;
  report.Add("a", Files().a).Add("b", Files().b).Add("out", Files().out).Merge(result.report);
  return WriteReport(report);
}

}  // namespace

extern const Command kBlendCommand = {
    "blend", "transition from one motion to another (multiresolution or weighted sum)",
    "mocapsolve blend --a=A.bvh --b=B.bvh --transition=START:END [--method=multires|weighted]\n"
    "    --out=OUT.bvh\n\n"
    "Plays A, then B from A's frame --b_start (default START), blending over the window\n"
    "START:END (frames of A, 0-based, or seconds with an 's' suffix). weighted: the plain\n"
    "ease-in/ease-out weighted sum (Huang, Boulic & Thalmann, eq. 6); multires: the same\n"
    "weights applied per band of Laplacian pyramids (section 3), which spreads each band's\n"
    "seam over its own wavelength. Rotations are blended as sign-continuous quaternions\n"
    "(B's sign matched to A's at START) and renormalized (nlerp). Prints the largest\n"
    "velocity jump near the window and in each input.",
    __FILE__, BlendMain,
    {SharedOptions("a,b,out,skeleton,skeleton_units,amc_fps,animation,sample_fps,report"),
     PyramidSettingOptions().options(), BlendMethodOption().options(), BlendSettingOptions().options()}};

}  // namespace mocapsolve
