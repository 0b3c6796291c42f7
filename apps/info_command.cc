// mocapsolve info FILE: what a motion file holds.
#include <cstdio>
#include <limits>

#include "apps/command.h"
#include "apps/common_flags.h"
#include "io/motion_file.h"

namespace mocapsolve {
namespace {

Status RunInfo(const std::vector<std::string>& arguments) {
  if (arguments.size() != 1) return Status::Error("expected one file (mocapsolve info FILE)");
  const std::string& path = arguments[0];
  Skeleton skeleton;
  Motion motion;
  Status status = LoadMotion(path, &skeleton, &motion);
  if (!status.ok()) return status;

  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Pose& pose : motion.frames) {
    lo = lo.cwiseMin(pose.translations[0]);
    hi = hi.cwiseMax(pose.translations[0]);
  }
  if (motion.frames.empty()) lo = hi = Eigen::Vector3d::Zero();
  const LengthUnit& unit = skeleton.unit();
  std::printf("file:      %s\n", path.c_str());
  std::printf("joints:    %d (+%zu end sites), root '%s'\n", skeleton.num_joints(),
              skeleton.end_sites().size(), skeleton.name(0).c_str());
  std::printf("frames:    %d at %.6g fps (%.4g s)\n", motion.num_frames(), motion.frame_rate,
              motion.duration_seconds());
  if (unit.known()) {
    std::printf("units:     %s (%.6g m per unit)\n", unit.name.c_str(), unit.metres_per_unit);
  } else {
    std::printf("units:     not stated by the file (lengths below are in file units)\n");
  }
  std::printf("root path: min (%.4g, %.4g, %.4g) max (%.4g, %.4g, %.4g) extent (%.4g, %.4g, %.4g)\n",
              lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z(), hi.x() - lo.x(), hi.y() - lo.y(),
              hi.z() - lo.z());
  JsonObject report;
  report.Add("file", path)
      .Add("joints", skeleton.num_joints())
      .Add("end_sites", static_cast<int>(skeleton.end_sites().size()))
      .Add("frames", motion.num_frames())
      .Add("frame_rate", motion.frame_rate)
      .Add("duration_s", motion.duration_seconds())
      .Add("units", unit.name)
      .Add("metres_per_unit", unit.metres_per_unit)
      .Add("root_min", std::vector<JsonValue>{lo.x(), lo.y(), lo.z()})
      .Add("root_max", std::vector<JsonValue>{hi.x(), hi.y(), hi.z()});
  return WriteReport(report);
}

}  // namespace

extern const Command kInfoCommand = {
    "info", "joints, frames, frame rate, duration, units and root path of a motion file",
    "mocapsolve info FILE.bvh | FILE.amc --skeleton=FILE.asf [--report=info.json]\n\n"
    "Prints the joint and end-site counts, frame count and rate, duration, the file's\n"
    "length unit (BVH does not state one) and the bounding box of the root's path.",
    __FILE__, RunInfo, "skeleton,amc_fps,report"};

}  // namespace mocapsolve
