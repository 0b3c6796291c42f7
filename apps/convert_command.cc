// mocapsolve convert IN OUT: motion files to BVH, or into a glTF character; marker files
// between C3D and TRC.
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/delivery_flags.h"
#include "apps/option_flags.h"
#include "kinematics/quote_token.h"
#include "tasks/convert_task.h"


namespace mocapsolve {
namespace {

Status ConvertMain(const std::vector<std::string>& arguments) {
  if (arguments.size() != 2) return Status::Error("expected IN OUT (mocapsolve convert IN OUT)");
  ConvertInputs inputs;
  inputs.in = arguments[0];
  inputs.out = arguments[1];
  inputs.target = Files().target;
  inputs.motion = MotionReadOptionsOf(FileReading(), Files().skeleton);  // --animation: an error for one-clip formats.
  inputs.axes = FileReading().axes;
  ConvertSettings settings;
  ReadOptionFlags(ConvertSettingOptions(), &settings);
  ClipDelivery delivery;
  Status status = ClipDeliveryFromFlags(&delivery);
  if (!status.ok()) return status;
  ConvertResult result;
  status = RunConvert(inputs, settings, delivery, &result);
  for (const std::string& warning : result.warnings) {
    std::fprintf(stderr, "warning: %s\n", TerminalText(warning).c_str());
  }
  if (!status.ok()) return status;
  std::fputs(result.summary.c_str(), stdout);
  return WriteReport(result.report);
}

}  // namespace

extern const Command kConvertCommand = {
    "convert", "BVH, ASF/AMC, glTF/GLB or FBX in; BVH or FBX out, or a new clip of a glTF character",
    "mocapsolve convert IN.bvh|IN.amc|IN.glb|IN.gltf|IN.fbx OUT.bvh [--skeleton=X.asf] "
    "[--animation=NAME] [--scale=S] [--euler_order=ZXY]\n"
    "       mocapsolve convert IN OUT.glb|OUT.gltf [--target=CHARACTER.glb] [--clip_name=NAME]\n"
    "       mocapsolve convert IN OUT.fbx [--target=CHARACTER.glb] [--clip_name=NAME] [--euler_order=XYZ]\n"
    "       mocapsolve convert IN.c3d|IN.trc OUT.c3d|OUT.trc [--out_units=mm] [--axes=y,z,x]\n\n"
    "Reads a motion and writes it as BVH. Rest rotations of ASF skeletons are folded into\n"
    "the BVH rotation channels. With a .glb/.gltf OUT, the motion (whose skeleton must have\n"
    "the character's joints, e.g. a BVH converted from it) is added as a new animation to a\n"
    "copy of --target (default IN). With a .fbx OUT, binary FBX 7.4: the skeleton and the\n"
    "clip (take --clip_name), or with --target (default a glTF IN) the character, its skinned\n"
    "mesh and the clip. Marker files convert between C3D and TRC: labels, rate,\n"
    "first frame and missing samples kept, in --out_units, OUT's axes being IN's --axes.\n"
    "--frames=A:B or --seconds=A:B cut the motion, --out_fps=R resamples it (BVH, glTF, FBX).\n"
    "OUT is written atomically and may not be an input.",
    __FILE__, ConvertMain,
    {SharedOptions("skeleton,skeleton_units,amc_fps,animation,sample_fps,target,axes,include_model_outputs,"
                   "subject_prefix,ignore_markers,report"),
     ConvertSettingOptions().options(), DeliverySettingOptions().Without("formats").options()}};

}  // namespace mocapsolve
