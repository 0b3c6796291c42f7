// Reading a skeleton motion from whatever file the user names: .bvh on its own, an
// Acclaim .amc with its .asf skeleton, a glTF character (.glb/.gltf: skin 0 and one of
// its animations, see io/gltf_reader.h; metres) or an FBX (.fbx: the animated node
// hierarchy and one animation, see io/fbx_reader.h; the file's unit). The extension
// decides (case-insensitive).
#ifndef MOCAPSOLVE_IO_MOTION_FILE_H_
#define MOCAPSOLVE_IO_MOTION_FILE_H_

#include <string>
#include <vector>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct MotionFileOptions {
  std::string skeleton_path;      // The .asf for an .amc; must be empty for a .bvh.
  double amc_frame_rate = 120.0;  // AMC files do not store their rate; CMU's is 120 Hz.
  // glTF/FBX: the animation (name or index; "" = the first) and the sampling rate (0 =
  // the key rate when uniform, else 30 fps). Must stay at their defaults for BVH/AMC.
  std::string animation;
  double sample_rate = 0.0;
  // The unit of a skeleton whose file states none (SetSkeletonUnits; "" = leave it).
  std::string skeleton_units;
  // If not null, receives the reader's warnings (approximated scales, ignored channels).
  std::vector<std::string>* warnings = nullptr;
};

Status ReadMotionFile(const std::string& path, const MotionFileOptions& options,
                      Skeleton* skeleton, Motion* motion);

// The skeleton of a .bvh (its motion is ignored), an .asf, a .glb/.gltf (skin 0) or an
// .fbx (the hierarchy animated by its first animation). *asf_info, if not null,
// receives the ASF's dofs and limits (left empty for the other formats).
struct AsfInfo;
Status ReadSkeletonFile(const std::string& path, Skeleton* skeleton, AsfInfo* asf_info = nullptr);

// The clips of a file that can hold several (.glb/.gltf/.fbx; "" for an unnamed one);
// empty for the other formats.
Status ReadAnimationNames(const std::string& path, std::vector<std::string>* names);

// Gives a skeleton whose file states no unit (a BVH) the unit `name` ("mm", "cm", "m",
// "in"; "" leaves it alone). An error (naming --skeleton_units, as the flag and the Python
// keyword are called) if the name is unknown or the file states another unit.
Status SetSkeletonUnits(const std::string& name, Skeleton* skeleton);

// Commands and pipelines that compute on frames refuse a motion without any, naming the
// file: "<path>: the motion has no frames (this command needs at least one)".
Status RequireFrames(const std::string& path, const Motion& motion);

// Lower-case extension with the dot (".bvh"), or "".
std::string FileExtension(const std::string& path);
// The name check of a text output (.bvh, .csv, .json, .svg, .html): `path` has
// `extension`, or is "-", the standard output (io/atomic_file.h). Binary outputs (.c3d,
// .glb) test FileExtension alone, so "-" is refused for them.
bool IsTextOutputPath(const std::string& path, const std::string& extension);
// The file name without folder and extension: "takes/02_05.c3d" -> "02_05".
std::string FileStem(const std::string& path);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_MOTION_FILE_H_
