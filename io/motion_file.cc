#include "io/motion_file.h"

#include <cctype>
#include <cmath>

#include "kinematics/marker_trajectories.h"

#include "io/amc_reader.h"
#include "io/atomic_file.h"
#include "io/asf_reader.h"
#include "io/bvh_reader.h"
#include "io/fbx_reader.h"
#include "io/gltf_reader.h"
#include "io/input_limits.h"

namespace mocapsolve {

std::string FileExtension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool IsTextOutputPath(const std::string& path, const std::string& extension) {
  return IsStandardOutput(path) || FileExtension(path) == extension;
}

std::string FileStem(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = name.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? name : name.substr(0, dot);
}

Status ReadAnimationNames(const std::string& path, std::vector<std::string>* names) {
  const std::string ext = FileExtension(path);
  names->clear();
  if (ext == ".glb" || ext == ".gltf") {
    GltfCharacter character;
    Status status = ReadGltfCharacter(path, GltfReadOptions(), &character);
    if (!status.ok()) return status;
    *names = character.animation_names;
  } else if (ext == ".fbx") {
    Skeleton skeleton;
    Motion motion;
    FbxInfo info;
    Status status = ReadFbx(path, FbxReadOptions(), &skeleton, &motion, &info);
    if (!status.ok()) return status;
    *names = info.animation_names;
  }
  return Status::Ok();
}

namespace {

// Every motion format's reader, then one check of what every writer can represent
// (io/input_limits.h), so that no format lets a rate of 1e-308 Hz or a root at 1e308 in.
Status CheckRead(const std::string& path, Status read, const Skeleton& skeleton, const Motion* motion) {
  if (!read.ok()) return read;
  Motion skeleton_only;
  skeleton_only.frame_rate = kMaxFrameRate;
  Status status = CheckMotionBounds(skeleton, motion != nullptr ? *motion : skeleton_only);
  return status.ok() ? status : Status::Error(path + ": " + status.message());
}

Status ReadSkeletonFileUnchecked(const std::string& path, Skeleton* skeleton, AsfInfo* asf_info);
Status ReadMotionFileUnchecked(const std::string& path, const MotionFileOptions& options,
                               Skeleton* skeleton, Motion* motion);

}  // namespace

Status ReadSkeletonFile(const std::string& path, Skeleton* skeleton, AsfInfo* asf_info) {
  return CheckRead(path, ReadSkeletonFileUnchecked(path, skeleton, asf_info), *skeleton, nullptr);
}

Status ReadMotionFile(const std::string& path, const MotionFileOptions& options,
                      Skeleton* skeleton, Motion* motion) {
  Status status = ReadMotionFileUnchecked(path, options, skeleton, motion);
  // An .amc's skeleton comes from its .asf: name that file for the skeleton's offsets.
  if (FileExtension(path) == ".amc") status = CheckRead(options.skeleton_path, status, *skeleton, nullptr);
  status = CheckRead(path, status, *skeleton, motion);
  return status.ok() ? SetSkeletonUnits(options.skeleton_units, skeleton) : status;
}

namespace {

Status ReadSkeletonFileUnchecked(const std::string& path, Skeleton* skeleton, AsfInfo* asf_info) {
  const std::string ext = FileExtension(path);
  if (ext == ".bvh") {
    Motion ignored;
    if (asf_info != nullptr) *asf_info = AsfInfo();
    return ReadBvh(path, skeleton, &ignored);
  }
  if (ext == ".asf") {
    AsfInfo info;
    Status status = ReadAsf(path, skeleton, &info);
    if (status.ok() && asf_info != nullptr) *asf_info = std::move(info);
    return status;
  }
  if (ext == ".glb" || ext == ".gltf") {
    GltfCharacter character;
    Status status = ReadGltfCharacter(path, GltfReadOptions(), &character);
    if (!status.ok()) return status;
    if (asf_info != nullptr) *asf_info = AsfInfo();
    *skeleton = character.skeleton;
    return Status::Ok();
  }
  if (ext == ".fbx") {
    Motion ignored;
    if (asf_info != nullptr) *asf_info = AsfInfo();
    return ReadFbx(path, FbxReadOptions(), skeleton, &ignored);
  }
  return Status::Error(path + ": unknown skeleton format '" + ext +
                       "' (expected .bvh, .asf, .glb, .gltf or .fbx)");
}

Status ReadMotionFileUnchecked(const std::string& path, const MotionFileOptions& options,
                               Skeleton* skeleton, Motion* motion) {
  const std::string ext = FileExtension(path);
  const bool animated_format = ext == ".glb" || ext == ".gltf" || ext == ".fbx";
  if (!animated_format && (!options.animation.empty() || options.sample_rate != 0.0)) {
    return Status::Error(path + ": an animation name or sample rate applies to .glb/.gltf/.fbx only");
  }
  if (animated_format && !options.skeleton_path.empty()) {
    return Status::Error(path + ": a " + ext + " carries its own skeleton; drop --skeleton");
  }
  if (ext == ".glb" || ext == ".gltf") {
    GltfDocument document;
    Status status = GltfDocument::Read(path, &document);
    if (!status.ok()) return status;
    GltfCharacter character;
    status = ReadGltfCharacter(document, GltfReadOptions(), &character);
    if (!status.ok()) return status;
    GltfAnimationOptions animation;
    animation.animation = options.animation;
    animation.frame_rate = options.sample_rate;
    Motion sampled;
    std::vector<std::string> clip_warnings;
    status = ReadGltfAnimation(document, character, animation, &sampled, &clip_warnings);
    if (!status.ok()) return status;
    if (options.warnings != nullptr) {
      *options.warnings = character.warnings;
      options.warnings->insert(options.warnings->end(), clip_warnings.begin(), clip_warnings.end());
    }
    *skeleton = character.skeleton;
    *motion = std::move(sampled);
    return Status::Ok();
  }
  if (ext == ".fbx") {
    FbxReadOptions fbx;
    fbx.animation = options.animation;
    fbx.frame_rate = options.sample_rate;
    FbxInfo info;
    Status status = ReadFbx(path, fbx, skeleton, motion, &info);
    if (status.ok() && options.warnings != nullptr) *options.warnings = info.warnings;
    return status;
  }
  if (ext == ".bvh") {
    if (!options.skeleton_path.empty()) {
      return Status::Error(path + ": a BVH carries its own skeleton; drop --skeleton");
    }
    return ReadBvh(path, skeleton, motion);
  }
  if (ext == ".amc") {
    if (options.skeleton_path.empty()) {
      return Status::Error(path + ": an AMC needs its skeleton: add --skeleton=FILE.asf");
    }
    if (!(options.amc_frame_rate > 0.0)) {
      return Status::Error("--amc_fps must be positive");
    }
    if (Status s = CheckFrameRate(options.amc_frame_rate, "--amc_fps"); !s.ok()) return s;
    AsfInfo info;
    Status status = ReadAsf(options.skeleton_path, skeleton, &info);
    if (!status.ok()) return status;
    return ReadAmc(path, *skeleton, info, options.amc_frame_rate, motion);
  }
  return Status::Error(path + ": unknown motion format '" + ext +
                       "' (expected .bvh, .amc, .glb, .gltf or .fbx)");
}

}  // namespace

Status RequireFrames(const std::string& path, const Motion& motion) {
  if (motion.num_frames() > 0) return Status::Ok();
  return Status::Error(path + ": the motion has no frames (this command needs at least one)");
}

Status SetSkeletonUnits(const std::string& name, Skeleton* skeleton) {
  if (name.empty()) return Status::Ok();
  const LengthUnit unit = LengthUnitFromName(name);
  if (!unit.known()) return Status::Error("--skeleton_units='" + name + "': expected mm, cm, m or in");
  if (skeleton->unit().known()) {
    if (std::abs(skeleton->unit().metres_per_unit / unit.metres_per_unit - 1.0) < 1e-12) return Status::Ok();
    return Status::Error("--skeleton_units=" + name + ": the skeleton file states its unit ('" +
                         skeleton->unit().name + "'); the flag is for files that do not");
  }
  std::vector<JointSpec> joints;
  for (int j = 0; j < skeleton->num_joints(); ++j) joints.push_back(skeleton->joint(j));
  Skeleton with_unit;
  Status status = Skeleton::Create(std::move(joints), skeleton->end_sites(), unit, &with_unit);
  if (!status.ok()) return status;
  *skeleton = std::move(with_unit);
  return Status::Ok();
}

}  // namespace mocapsolve
