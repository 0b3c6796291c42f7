// Reading a skeleton motion from whatever file the user names: .bvh on its own, or an
// Acclaim .amc with its .asf skeleton. The extension decides (case-insensitive).
#ifndef MOCAPSOLVE_IO_MOTION_FILE_H_
#define MOCAPSOLVE_IO_MOTION_FILE_H_

#include <string>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct MotionFileOptions {
  std::string skeleton_path;      // The .asf for an .amc; must be empty for a .bvh.
  double amc_frame_rate = 120.0;  // AMC files do not store their rate; CMU's is 120 Hz.
};

Status ReadMotionFile(const std::string& path, const MotionFileOptions& options,
                      Skeleton* skeleton, Motion* motion);

// The skeleton of a .bvh (its motion is ignored) or an .asf. *asf_info, if not null,
// receives the ASF's dofs and limits (left empty for a BVH).
struct AsfInfo;
Status ReadSkeletonFile(const std::string& path, Skeleton* skeleton, AsfInfo* asf_info = nullptr);

// Lower-case extension with the dot (".bvh"), or "".
std::string FileExtension(const std::string& path);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MOTION_FILE_H_
