// mocapsolve generate --out=demo.bvh: the project's own procedural demo clip.
#include <cstdio>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/option_flags.h"
#include "io/bvh_writer.h"
#include "io/motion_file.h"
#include "kinematics/demo_character.h"
#include "settings/demo_clip_settings.h"


namespace mocapsolve {
namespace {

Status RunGenerate(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().demo_out.empty() || !IsTextOutputPath(Files().demo_out, ".bvh")) {
    return Status::Error("--demo_out=FILE.bvh is required");
  }
  DemoClipSettings clip;
  ReadOptionFlags(DemoClipSettingOptions(), &clip);
  const Skeleton skeleton = MakeDemoSkeleton();
  const Motion motion = MakeDemoWalk(skeleton, clip.frames, clip.fps);
  Status status = WriteBvh(Files().demo_out, skeleton, motion, BvhWriteOptions());
  if (!status.ok()) return status;
  std::printf("wrote %s: procedural walk, %d joints, %d frames at %g fps, cm, Y up\n",
              Files().demo_out.c_str(), skeleton.num_joints(), motion.num_frames(), clip.fps);
  return Status::Ok();
}

}  // namespace

extern const Command kGenerateCommand = {
    "generate", "write the project's procedural demo clip (a walk-like BVH)",
    "mocapsolve generate --demo_out=demo.bvh [--frames=240] [--fps=60]\n\n"
    "A 20-joint character in cm, Y up, walking along +Z with swinging arms and legs;\n"
    "made by the project itself, so demos and tests need no external data.",
    __FILE__, RunGenerate,
    {SharedOptions("demo_out"),
     DemoClipSettingOptions().options()}};

}  // namespace mocapsolve
