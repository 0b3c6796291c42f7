// The skeleton as an Orocos KDL tree (liborocos-kdl-dev 1.5), for the peers benchmark.
//
// Segments, from KDL's root: the root joint is three prismatic segments (TransX, TransY,
// TransZ: the root translation), a fixed segment Frame(R_rest_0) and three revolute ones
// (RotX, RotY, RotZ); every other joint j is a fixed segment Frame(R_rest_j, offset_j)
// hooked on its parent's last segment, then RotX, RotY, RotZ. So a ball joint is three
// revolute joints, R_j = Rx(a) Ry(b) Rz(c) (XYZ Euler angles from our quaternion), and
// the tree has 3 + 3 #J joints, as our pose tangent. Marker m is an end segment on a fixed
// joint, Frame(z_m) on its joint's last segment.
//
// FK of every joint: one preorder walk frame_s = frame_parent(s) * Segment::pose(q_s)
// (KDL's own segment math; TreeFkSolverPos_recursive answers one segment per call, walking
// from the root each time, which would only be slower). Jacobian: TreeJntToJacSolver per
// marker segment (6 x #q, the position rows kept). IK: TreeIkSolverPos_NR_JL with the
// marker segments as endpoints, TreeFkSolverPos_recursive and TreeIkSolverVel_wdls whose
// task-space weight keeps the 3 position rows of each endpoint and zeroes the 3 rotation
// rows (markers are points), damping lambda (setLambda), joint limits +-1e9 (none), eps
// = sqrt(#markers) * target RMS (the solver's residual is the stacked position error's
// norm), at most target.max_iterations iterations.
#ifndef MOCAPSOLVE_BENCH_PEERS_KDL_TREE_H_
#define MOCAPSOLVE_BENCH_PEERS_KDL_TREE_H_

#include <memory>

#include "bench/peers/peer_model.h"

namespace mocapsolve::peers {

std::unique_ptr<PeerModel> MakeKdlTree(const Skeleton& skeleton, const MarkerSet& markers);

}  // namespace mocapsolve::peers

#endif  // MOCAPSOLVE_BENCH_PEERS_KDL_TREE_H_
