// FBX writer: a skeleton and one clip (optionally a skinned mesh) as binary FBX 7.4, the
// version Blender, assimp, Maya, MotionBuilder, Unreal and Unity all import. The
// container is io/fbx_binary.h; this file decides what the scene holds.
//
// Scene (Objects and Connections):
// - Each joint is a Model of type LimbNode with a NodeAttribute (LimbNode, TypeFlags
//   "Skeleton"), parented as in the skeleton (the root under the scene root). Its default
//   transform is Lcl Translation = t_j and Lcl Rotation = R_j of FbxWriteOptions::rest_pose
//   (default: the offsets and identity), and PreRotation = R_rest_j where the skeleton has a
//   rest rotation (RotationActive = 1 on every joint, so importers apply PreRotation and
//   RotationOrder). FBX composes a model's local transform as
//       T(Lcl Translation) * PreRotation * R(Lcl Rotation) * S,
//   which is the skeleton's T(t_j) * R_rest_j * R_j (skeleton.h), so world transforms are
//   ours. End sites are LimbNode models without animation (Blender's "_end" bones).
// - Rotation order: FBX names the axis applied first (eEulerXYZ: R = Rz Ry Rx), our
//   EulerOrder the leftmost factor (kZYX: R = Rz Ry Rx), so FBX's order is ours reversed.
//   Each joint keeps the order of its file's rotation channels (a BVH's), else XYZ, unless
//   FbxWriteOptions::euler_order overrides it; RotationOrder records it. PreRotation is
//   XYZ (as the FBX SDK, assimp and current Blender read it; Blender 3.4 applies the joint's
//   RotationOrder to it), so a joint with a rest rotation is always written in XYZ, which
//   every reader evaluates alike.
// - Animation: one AnimationStack (FbxWriteOptions::take_name) with one AnimationLayer.
//   Per joint that turns from its default rotation in some frame (and for the root) an
//   AnimationCurveNode "R" on Lcl Rotation with three AnimationCurves (degrees, float keys;
//   a joint that never turns has none, and importers keep its Lcl Rotation), and for the root and every joint whose translation leaves its rest value
//   in some frame (by more than 1e-9 (|t| + 1)) a curve node "T" on Lcl Translation. Keys at
//   every frame, KeyTime = round(k * 46186158000 / frame_rate) FBX ticks (a rate within 1e-5
//   of a whole number taken as that number: a BVH's 0.00833333 s frame time is 120 fps), linear
//   interpolation; a curve whose values are all equal has two keys (the first and last frame).
//   With FbxWriteOptions::key_tolerance_mm = E > 0 the keys are reduced
//   (io/curve_key_reduction.h) so that no joint or end site moves by more than E: a point p
//   is moved by m(p) curve sets (the translation curves of p and of each joint above it, the
//   rotation curves of each joint strictly above it); joint j's set gets the share E / M_j,
//   M_j the largest m(p) over the points it moves: its translation curves within E / M_j
//   (file units), its rotation curves within E / (3 r_j M_j) radians, r_j its reach (the
//   longest path of offsets to a point below it; a leaf's own bone length), as three Euler
//   angles each off by tau turn the joint by at most 3 tau, which moves a point r away by
//   3 tau r. The shares along any path add to at most E. Angles are unrolled per
//   joint: each frame takes, of the two Euler triples of its rotation, (a, b, c) and
//   (a + 180, 180 - b, c + 180), shifted by multiples of 360 per component, the one nearest
//   the previous frame's, so consecutive keys never jump by 360 (angles may leave
//   (-180, 180]: a joint that turns twice ends near 720).
// - Skinned mesh (optional): a Mesh model at the origin with a Geometry (Vertices = the
//   rest positions, PolygonVertexIndex = the triangles, the last index of each stored as
//   ~index; normals ByVertice when the mesh has them; its texture coordinates, where it
//   has them, as LayerElementUV "UVMap": ByPolygonVertex, IndexToDirect, one (u, 1 - v) per
//   vertex indexed by the triangles, FBX's v running up where glTF's runs down), one grey Phong Material, a Skin
//   deformer with one Cluster per joint (Indexes/Weights of the vertices it moves,
//   TransformLink = the joint's world transform at bind = joint_from_bind^-1, Transform =
//   joint_from_bind, the mesh being at the origin) and a BindPose listing the mesh and
//   every joint with those world matrices.
// - GlobalSettings: Y up, Z front, X coordinate axis (right-handed, FBX's and Maya's
//   default and the axes of glTF and of BVH as mocap writes it), UnitScaleFactor = the
//   centimetres per file unit (lengths are written in the skeleton's unit as they are: 100
//   for metres, 1 for cm; a skeleton without a unit, a BVH, is taken to be in cm unless
//   FbxWriteOptions::unit_scale_factor says otherwise), TimeMode from the frame rate (the
//   FBX enum for 24, 25, 30, 48, 50, 60, 72, 96, 100, 120 fps; else custom with
//   CustomFrameRate), TimeSpan = the clip. Takes holds the take too.
//
// Errors (nothing is written): a joint name FBX cannot hold (empty, embedded NUL, the
// "\x00\x01" separator, over 2^31 bytes) names the joint; a joint or end site more than
// kMaxFbxSkeletonDepth levels below the root names it (FBX itself nests models through
// Connections without a bound, but Blender 3.4's importer recurses in Python once per
// level and fails with a RecursionError on a 999-joint chain; 980 imports); a motion that does not fit the
// skeleton, a non-positive frame rate, no frames; a mesh whose sizes do not match. Output
// is written atomically (io/atomic_file.h).
#ifndef MOCAPSOLVE_IO_FBX_WRITER_H_
#define MOCAPSOLVE_IO_FBX_WRITER_H_

#include <optional>
#include <string>

#include <Eigen/Core>

#include "io/gltf_reader.h"
#include "kinematics/compact_motion.h"
#include "kinematics/motion.h"
#include "kinematics/rotation.h"
#include "kinematics/skeleton.h"
#include "kinematics/skinned_mesh.h"
#include "kinematics/status.h"

namespace mocapsolve {

// Deepest joint (levels below the root, end sites included) the writer writes: a margin
// under the ~990 levels where Blender 3.4's FBX importer runs out of Python recursion.
constexpr int kMaxFbxSkeletonDepth = 900;

struct FbxWriteOptions {
  std::string take_name = "Take 001";    // The AnimationStack's name; non-empty, no NUL.
  double unit_scale_factor = 0.0;        // Centimetres per file unit; 0 = from the skeleton's unit.
  std::optional<EulerOrder> euler_order;  // Overrides every joint's rotation order (ours, see above).
  std::optional<Pose> rest_pose;         // The models' default transforms (GltfCharacter::rest_pose).
  double key_tolerance_mm = 0.0;         // Key reduction bound, mm (see Animation above); 0 = exact.
};

// A skinned mesh bound to the skeleton written (SkinnedMesh: rest positions in bind space).
struct FbxSkinnedMesh {
  const SkinnedMesh* mesh = nullptr;
  const Eigen::Matrix3Xi* triangles = nullptr;  // 3 x #T vertex indices, counter-clockwise.
  std::string name = "mesh";
};

// The file's bytes; `mesh` may be null (skeleton and clip only).
Status SerializeFbx(const Skeleton& skeleton, const Motion& motion, const FbxWriteOptions& options,
                    const FbxSkinnedMesh* mesh, std::string* bytes);

Status WriteFbx(const std::string& path, const Skeleton& skeleton, const Motion& motion,
                const FbxWriteOptions& options = FbxWriteOptions(), const FbxSkinnedMesh* mesh = nullptr);

// A glTF character with a clip of it (e.g. retargeted): its skeleton at its rest pose
// (the nodes' default TRS), its skinned mesh ("mesh", all primitives of the skin merged)
// unless `animation_only`, and the clip as the take `take_name`.
Status WriteFbxCharacter(const std::string& path, const GltfCharacter& character, const Motion& motion,
                         const std::string& take_name, bool animation_only, double key_tolerance_mm = 0.0);
// The same from a CompactMotion, read one joint of one frame at a time (io/motion_samples.h):
// a long take is not expanded whole to be written; the same bytes as its ToMotion().
Status WriteFbxCharacter(const std::string& path, const GltfCharacter& character, const CompactMotion& motion,
                         const std::string& take_name, bool animation_only, double key_tolerance_mm = 0.0);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_FBX_WRITER_H_
