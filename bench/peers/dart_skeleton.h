// The skeleton as a DART 6.12 dynamics::Skeleton (libdart-dev), for the peers benchmark.
//
// Body 0 hangs on a FreeJoint (positions: rotation vector, then translation, of
// T(t) R_rest_0 R_0); body j on a BallJoint (positions: the rotation vector of R_j, DART's
// exp coordinates) whose transform from the parent body is T(offset_j) R_rest_j. So the
// skeleton has 6 + 3 (#J - 1) = 3 + 3 #J dofs. Marker m is an EndEffector on its joint's
// body, default relative transform T(z_m).
//
// FK: Skeleton::setPositions, then every body's and end effector's getWorldTransform
// (DART computes transforms lazily, on request). Jacobian: Skeleton::getLinearJacobian of
// each end effector (3 x #dofs, world frame).
//
// IK: each marker's end effector gets an InverseKinematics module (getIK(true)) whose
// target is a SimpleFrame at the observed position, orientation ignored (angular bounds
// +-inf), and the skeleton's WholeBodyIK (a HierarchicalIK: every module at level 0)
// solves them together with its optimizer::GradientDescentSolver, through
// solveAndApply(). DartIkSettings holds the knobs the benchmark varies; each module's
// gradient method is JacobianDLS (DART's default, damping `damping`) or
// JacobianTranspose. The solver runs `chunk` iterations per solveAndApply call, and the
// RMS residual is checked between calls against the target, up to max_iterations.
#ifndef MOCAPSOLVE_BENCH_PEERS_DART_SKELETON_H_
#define MOCAPSOLVE_BENCH_PEERS_DART_SKELETON_H_

#include <memory>
#include <string>

#include "bench/peers/peer_model.h"

namespace mocapsolve::peers {

struct DartIkSettings {
  std::string gradient = "dls";  // dls (JacobianDLS) | transpose (JacobianTranspose)
  double damping = 0.05;         // JacobianDLS damping (DART's default, DefaultIKDLSCoefficient).
  double step_size = 0.1;        // GradientDescentSolver step multiplier (DART's default).
  double linear_bound = 1e-6;    // Per-axis position error counted as zero (DART's default).
  int chunk = 10;                // Solver iterations per solveAndApply call.
};

std::unique_ptr<PeerModel> MakeDartSkeleton(const Skeleton& skeleton, const MarkerSet& markers,
                                            const DartIkSettings& ik);

}  // namespace mocapsolve::peers

#endif  // MOCAPSOLVE_BENCH_PEERS_DART_SKELETON_H_
