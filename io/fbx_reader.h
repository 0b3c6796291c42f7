// FBX reader (through assimp): the animated node hierarchy of an FBX as a Skeleton and
// one animation as a Motion. Meant for skeleton-only mocap FBX files (the CMU clips in
// shared/data/fbx: a Blender export of the cgspeed BVH); meshes and skins are only counted
// (FbxInfo) and name the skeleton of a file without animation
// (FbxReadOptions::skeleton_without_animation); cameras are ignored.
//
// Skeleton: the joints are the nodes with an animation channel in the chosen animation,
// the nodes on the paths between them, the root: the lowest common ancestor of all
// animated nodes (an animated node itself in the CMU files: Hips), and the nodes below a
// joint that have children and no mesh (a still finger chain, which writers leave without
// curves). Preorder, children in file order. A non-animated leaf child of a joint
// (Blender's "*_end" nodes) becomes an EndSite. The root's ancestors (the armature object and assimp's root) are baked into
// the root: their rotation is the root's rest rotation and their translation and scale
// are applied to its translation; node scales are baked into offsets exactly as in
// gltf_reader.h (uniform scales accumulated; a non-uniform scale is approximated by the
// cube root of |sx sy sz| with a warning). assimp's pivot helper nodes are disabled
// (AI_CONFIG_IMPORT_FBX_PRESERVE_PIVOTS = false), so each FBX Model is one node.
//   Pose: translation_j = c_p * t_j(t), rotation_j = R_rest_j^-1 * R_chain(t) (R_rest = the
// constant rotation of baked ancestors; identity for all joints below the root), so the
// skeleton's world transforms equal the FBX's global node transforms with scale removed.
//
// Units: FBX GlobalSettings UnitScaleFactor is the number of centimetres per file unit
// (1.0 = cm, 100 = m). The skeleton's unit is that: {"cm", 0.01} for 1.0, otherwise
// {"fbx unit (N cm)", N / 100}. Lengths stay in file units (no rescale); ask the
// skeleton's unit to convert. The CMU clips state 1.0 (cm) but hold the cgspeed values,
// which are in CMU units; a Blender import applies a 0.01 armature scale. See the test
// for the heights measured.
//
// Animation (by name or index, default 0): sampled at the key rate (as in gltf_reader.h:
// the smallest key spacing if all are multiples of it; else 30 fps; or
// FbxReadOptions::frame_rate), from the earliest key
// to the latest; between keys lerp/slerp, outside them the end keys hold. Scale keys
// are used when uniform and constant over the clip, otherwise ignored with a warning.
// Rotation series are sign-continuous.
//
// Errors: Status with one line naming the file ("run.fbx: assimp: ..." for parse errors,
// "run.fbx: animation 'X' not found (animations: ...)").
//
// Hostile input: an ASCII FBX nested more than kMaxThirdPartyNesting braces deep is
// refused before assimp sees it (io/input_limits.h); then assimp parses the bytes once in
// a forked child process, and a child that crashes (e.g. Debian's assimp double-frees on
// duplicate model names) or runs past 60 s becomes an error ("run.fbx: assimp crashed
// parsing the file (signal 6, Aborted)"); only then are the bytes parsed in this process.
// So every FBX is parsed twice. A node hierarchy deeper than 1000 levels is an error.
#ifndef MOCAPSOLVE_IO_FBX_READER_H_
#define MOCAPSOLVE_IO_FBX_READER_H_

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct FbxReadOptions {
  std::string animation;    // Name or index; "" = animation 0.
  double frame_rate = 0.0;  // 0 = the key rate if uniform, else 30.
  // A file without animation (a rigged character) is an error unless this is set; then
  // the skeleton is read from its skinned meshes' bones (the nodes the skins name, the
  // nodes between them, their lowest common ancestor as the root, as above) and the
  // motion is one frame: the nodes' default transforms, the bind pose as the file stores
  // it (frame_rate, or 30). A file with neither animation nor skin is still an error.
  bool skeleton_without_animation = false;
};

struct FbxInfo {
  std::vector<std::string> animation_names;
  double unit_scale_factor = 1.0;  // Centimetres per file unit (FBX UnitScaleFactor).
  std::vector<std::string> warnings;
  int meshes = 0;                  // assimp meshes (one per material of an FBX geometry).
  int skinned_meshes = 0;          // With bones.
  long long vertices = 0;          // Over every mesh.
  int bones = 0;                   // Distinct nodes the skins name.
  // Every mesh instance's vertices in the world at the nodes' default transforms, file
  // units (3 x #V; empty past 1e7 vertices).
  Eigen::Matrix3Xd mesh_vertices;
  Pose default_pose;  // The skeleton's pose at the nodes' default transforms (bind pose as stored).
};

Status ReadFbx(const std::string& path, const FbxReadOptions& options, Skeleton* skeleton,
               Motion* motion, FbxInfo* info = nullptr);
// The bytes of an FBX file held in memory; error messages name `name_for_errors`.
Status ParseFbx(std::string_view bytes, const std::string& name_for_errors,
                const FbxReadOptions& options, Skeleton* skeleton, Motion* motion,
                FbxInfo* info = nullptr);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_FBX_READER_H_
