// mocapsolve fk --motion=FILE --out=positions.csv: global joint positions per frame.
#include <cstdio>
#include <string>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "apps/progress.h"
#include "io/atomic_file.h"
#include "io/motion_file.h"
#include "kinematics/forward_kinematics.h"


namespace mocapsolve {
namespace {

Status RunFk(const std::vector<std::string>& arguments) {
  if (!arguments.empty()) return Status::Error("unexpected argument '" + arguments[0] + "'");
  if (Files().motion.empty() || Files().out.empty()) {
    return Status::Error("--motion and --out are required");
  }
  if (!IsTextOutputPath(Files().out, ".csv")) return Status::Error(Files().out + ": expected a .csv");
  Status status = CheckNotAnInput(Files().out, Files().motion);
  if (!status.ok()) return status;
  Skeleton skeleton;
  Motion motion;
  status = LoadMotion(Files().motion, &skeleton, &motion);
  if (status.ok()) status = RequireFrames(Files().motion, motion);
  if (!status.ok()) return status;

  std::string csv = "frame,joint,x,y,z\n";
  csv.reserve(csv.size() + motion.frames.size() * skeleton.num_joints() * 48);
  FkData data(skeleton);
  Progress progress("fk", motion.num_frames(), Console().quiet);
  char line[256];
  for (int f = 0; f < motion.num_frames(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &data);
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      const Eigen::Vector3d& p = data.world_positions[j];
      std::snprintf(line, sizeof line, "%d,%s,%.9g,%.9g,%.9g\n", f, skeleton.name(j).c_str(),
                    p.x(), p.y(), p.z());
      csv += line;
    }
    progress.Update(f + 1);
  }
  status = WriteFileAtomically(Files().out, csv);
  if (!status.ok()) return status;
  std::printf("wrote %s: %d frames x %d joints (units: %s)\n", Files().out.c_str(),
              motion.num_frames(), skeleton.num_joints(), skeleton.unit().name.c_str());
  JsonObject report;
  report.Add("motion", Files().motion).Add("out", Files().out).Add("frames", motion.num_frames())
      .Add("joints", skeleton.num_joints()).Add("units", skeleton.unit().name);
  return WriteReport(report);
}

}  // namespace

extern const Command kFkCommand = {
    "fk", "global joint positions per frame to CSV",
    "mocapsolve fk --motion=FILE.bvh|FILE.amc|FILE.glb|FILE.fbx [--skeleton=X.asf] [--animation=NAME] --out=positions.csv\n\n"
    "Runs forward kinematics on every frame and writes one row per frame and joint:\n"
    "frame,joint,x,y,z (joints by name, lengths in the motion file's units).",
    __FILE__, RunFk, {SharedOptions("motion,out,skeleton,skeleton_units,amc_fps,animation,sample_fps,report")}};

}  // namespace mocapsolve
