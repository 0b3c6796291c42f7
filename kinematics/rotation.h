// Rotations: unit quaternions in the model, Euler angles only at the I/O boundary.
//
// Exp/log maps (Grassia 1998) use the rotation-vector convention: ExpMap(v) is the
// rotation by |v| radians about v/|v|; LogMap(q) returns v with |v| <= pi. Both are
// accurate near 0 (Taylor branches) and near pi (atan2, no acos).
//
// Euler angles are intrinsic, as BVH defines them: the order names the axes from left
// to right in the product, so EulerOrder::kZXY with angles (a, b, c) (radians) is
// R = Rz(a) * Rx(b) * Ry(c): the first angle belongs to the first axis named.
#ifndef MOCAPSOLVE_KINEMATICS_ROTATION_H_
#define MOCAPSOLVE_KINEMATICS_ROTATION_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mocapsolve {

enum class EulerOrder { kXYZ, kXZY, kYXZ, kYZX, kZXY, kZYX };

// "XYZ" -> kXYZ, case-insensitive; false for anything else.
bool ParseEulerOrder(const std::string& text, EulerOrder* order);
std::string EulerOrderName(EulerOrder order);
// Axis index (0 = x, 1 = y, 2 = z) of the i-th factor of the product, i in [0, 3).
int EulerAxis(EulerOrder order, int i);
EulerOrder EulerOrderFromAxes(int first, int second, int third);

// angles_rad[i] is the angle about EulerAxis(order, i).
Eigen::Quaterniond QuaternionFromEuler(const Eigen::Vector3d& angles_rad, EulerOrder order);
// Inverse of QuaternionFromEuler with the middle angle in [-pi/2, pi/2] and the outer
// two in (-pi, pi]. At gimbal lock (middle angle +-pi/2) the third angle is set to 0.
Eigen::Vector3d EulerFromQuaternion(const Eigen::Quaterniond& q, EulerOrder order);
Eigen::Vector3d EulerFromMatrix(const Eigen::Matrix3d& m, EulerOrder order);

// Angles of q about `axes` (1 to 3 distinct axes, product order: q = R_a0(t0) R_a1(t1)
// ...). Three axes: EulerFromQuaternion. Two: the first two angles of the decomposition
// completed by the remaining axis (exact when q is such a product). One: 2 atan2(q_a, w)
// wrapped into (-pi, pi]. If `rate` is not null it receives the k x 3 derivative of the
// angles of q exp(delta) at delta = 0 (delta a local increment): rows of M^-1 with
// M = [(R_b R_c)^T e_a, R_c^T e_b, e_c]; singular at gimbal lock.
void AnglesAboutAxes(const Eigen::Quaterniond& q, const std::vector<int>& axes, double* angles,
                     Eigen::Matrix<double, Eigen::Dynamic, 3>* rate = nullptr);

Eigen::Quaterniond ExpMap(const Eigen::Vector3d& rotation_vector);
Eigen::Vector3d LogMap(const Eigen::Quaterniond& q);

// Flips q[i] to -q[i] where that brings it nearer q[i-1] (q and -q are one rotation),
// so that a time series can be interpolated and differenced.
void MakeSignContinuous(std::vector<Eigen::Quaterniond>* series);

// [v]x, the cross-product matrix: SkewSymmetric(v) * w = v x w.
inline Eigen::Matrix3d SkewSymmetric(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Angle in radians, in [0, pi], of the rotation taking a to b.
double AngularDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

constexpr double kPi = 3.14159265358979323846;
inline double DegToRad(double deg) { return deg * (kPi / 180.0); }
inline double RadToDeg(double rad) { return rad * (180.0 / kPi); }

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_KINEMATICS_ROTATION_H_
