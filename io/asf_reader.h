// Acclaim ASF skeleton reader (ASF 1.10 as written by VICON BodyLanguage and used by the
// CMU Graphics Lab Motion Capture Database).
//
// Format. Line oriented; a line whose first non-blank character is '#' is a comment (CMU
// files, and fairmotion's copies with a '#' line 2). Sections start with a ':' keyword:
//   :version, :name          one value each (kept in AsfInfo);
//   :units                   "mass m", "length L", "angle deg|rad" (defaults 1, 1, deg);
//                            one length unit is 1/L inch (CMU: L = 0.45, 5.644 cm);
//   :documentation, others   free text, skipped up to the next ':' line;
//   :root                    "order TX TY TZ RX RY RZ" (the AMC root value order),
//                            "axis XYZ" (order of 'orientation'), "position x y z",
//                            "orientation x y z";
//   :bonedata                blocks "begin ... end" with "id n", "name s", "direction
//                            x y z" (world frame, at rest), "length L", "axis x y z XYZ",
//                            optionally "dof rx ry rz" (any subset of rx ry rz, in the
//                            order the AMC lists the values), "limits (lo hi)" per dof
//                            (may continue over lines, "inf" allowed), "bodymass",
//                            "cofmass";
//   :hierarchy               "begin", lines "parent child child ...", "end".
// Translation dofs on bones (tx ty tz l) are rejected as unsupported.
//
// Euler angles (Acclaim). Three angles about X, Y, Z with an order string are applied in
// the order written, each about the fixed world axes: "axis ax ay az XYZ" is
//   C = Rz(az) * Ry(ay) * Rx(ax)       (acting on column vectors; x applied first),
// and a dof list "rx ry rz" with AMC values (a, b, c) is M = Rz(c) * Ry(b) * Rx(a);
// missing dofs are zero. AcclaimEulerRotation implements both. Verified against the
// MotionBuilder BVH conversion of CMU 16_15 (tests/io/asf_amc_vs_bvh_test.cc): world
// joint positions and frames agree to the BVH's print rounding (max 0.0006 cm, 0.0015
// deg) on the frames MotionBuilder sampled; the reverse product order is off by
// centimetres.
//
// Acclaim kinematics: each bone b has a world rotation W_b = W_parent * C_b M_b C_b^-1
// (W_root = C_root M_root C_root^-1, C_root from 'orientation' in 'axis' order, M_root
// from the AMC root angles in 'order'), starts at its parent's tail (root children at
// the root position + AMC translation) and ends at start + W_b d_b L_b.
//
// Mapping into Skeleton (world_from_joint_j = world_from_joint_parent * T(t_j) *
// R_rest_j * R_j): one joint per bone, placed at the bone's START, with joint frame
// G_b = W_b C_b (so at rest the joint frame is C_b in the world). Then
//   root:  t = position (+ AMC TX TY TZ in the pose), R_rest = C_root, R = M_root;
//   bone:  R_rest_b = C_p^-1 C_b,  R_b = M_b       (C_p = C_root below the root),
//          t_b = C_p^-1 d_p L_p   (p the parent bone; zero when p is the root, which has
//                                  no length: root children start at the root),
// and every leaf bone gets an EndSite "<bone>_End" at its tail, offset C_b^-1 d_b L_b in
// its own frame. Joints are the :hierarchy in preorder (children in the listed order).
// Offsets stay in file units; Skeleton::unit() is AcclaimLength(L). Channels record the
// AMC value layout: the root's 'order' (positions and rotations), each bone's rotation
// dofs in dof order, none for bones without dofs. Read them as Acclaim order (the first
// listed is applied first: "rx ry rz" is BVH's "Zrotation Yrotation Xrotation"); a
// writer should take angles from the quaternions, not reuse these lists blindly.
//
// Errors are one line, "file:line: message". Every input yields a Status; no input
// crashes or hangs the reader.
#ifndef MOCAPSOLVE_IO_ASF_READER_H_
#define MOCAPSOLVE_IO_ASF_READER_H_

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

enum class AcclaimDof { kTx, kTy, kTz, kRx, kRy, kRz };

// "rx" -> "rx" etc.
std::string AcclaimDofName(AcclaimDof dof);
inline bool IsRotationDof(AcclaimDof dof) { return dof >= AcclaimDof::kRx; }
// 0, 1, 2 for x, y, z (of either kind).
inline int AcclaimDofAxis(AcclaimDof dof) { return static_cast<int>(dof) % 3; }

struct AsfDof {
  AcclaimDof dof = AcclaimDof::kRx;
  // Limits in degrees (whatever ':units angle' says), -inf/+inf when the file gives
  // none. Root dofs never have limits.
  double lower_deg = -std::numeric_limits<double>::infinity();
  double upper_deg = std::numeric_limits<double>::infinity();
};

struct AsfBone {
  std::string name;
  int id = 0;                 // The file's 'id' (0 if absent); not used for anything.
  int line = 0;               // 1-based line of the bone's 'begin'.
  int joint = -1;             // Index of the bone's joint in the Skeleton.
  int parent_joint = -1;      // Index of the parent's joint (0 for root children).
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // Unit, world frame at rest.
  double length = 0.0;                                   // File length units.
  Eigen::Vector3d axis_deg = Eigen::Vector3d::Zero();    // 'axis' angles x, y, z, degrees.
  std::string axis_order = "XYZ";                        // As written, upper case.
  Eigen::Quaterniond axis_rotation = Eigen::Quaterniond::Identity();  // C_b.
  std::vector<AsfDof> dofs;  // The file's order = the AMC value order.
};

struct AsfInfo {
  std::string version;
  std::string name;
  double mass_scale = 1.0;    // ':units mass'.
  double length_scale = 1.0;  // ':units length' L: one unit = 1/L inch.
  bool angles_in_degrees = true;  // ':units angle'; AsfBone/AsfDof angles are degrees anyway.

  std::vector<AsfDof> root_order;  // ':root order', the AMC root value order.
  std::string root_axis_order = "XYZ";
  Eigen::Vector3d root_position = Eigen::Vector3d::Zero();         // File units.
  Eigen::Vector3d root_orientation_deg = Eigen::Vector3d::Zero();  // Degrees.
  Eigen::Quaterniond root_axis_rotation = Eigen::Quaterniond::Identity();  // C_root.

  std::vector<AsfBone> bones;      // In :bonedata order.
  std::vector<int> bone_of_joint;  // #J: index into bones, -1 for the root (joint 0).

  // Index into bones, or -1 ("root" is not a bone).
  int FindBone(const std::string& name) const;
};

// Reads an ASF file; on error *skeleton and *info are unspecified.
Status ReadAsf(const std::string& path, Skeleton* skeleton, AsfInfo* info);
// The same on text already in memory; name_for_errors prefixes the messages.
Status ParseAsf(const std::string& text, const std::string& name_for_errors,
                Skeleton* skeleton, AsfInfo* info);

// Acclaim Euler rotation: angles_rad[i] about axis axes[i] (0 = x, 1 = y, 2 = z), applied
// in the given order, first one first: R = R_{axes[n-1]} * ... * R_{axes[0]}, n <= 3.
Eigen::Quaterniond AcclaimEulerRotation(int count, const int* axes, const double* angles_rad);
// "axis ax ay az ORDER" and root 'orientation': angles are about x, y, z; `order` is the
// written order string (e.g. "XYZ", assumed valid) in which they are applied.
Eigen::Quaterniond AcclaimAxisRotation(const Eigen::Vector3d& xyz_angles_rad,
                                       const std::string& order);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_ASF_READER_H_
