// The skeleton as a MuJoCo model (libmujoco-dev 2.2.2), for the peers benchmark. MuJoCo
// has no inverse kinematics, so it takes part in FK and the Jacobian only.
//
// The model is MJCF text generated from our skeleton and loaded with mj_loadXML (a
// temporary file, deleted once loaded): body j sits at pos = offset_j, quat = R_rest_j in
// its parent body (MuJoCo quaternions are w x y z), with a ball joint (qpos: 4 numbers,
// w x y z = R_j; 3 velocity dofs); the root body has a free joint (qpos: translation,
// then w x y z of R_rest_0 R_0; 6 dofs). Each body has a unit point mass (MuJoCo refuses
// massless moving bodies; kinematics ignore it). Marker m is a site at z_m in its
// joint's body. So nq = 7 + 4 (#J - 1) and nv = 3 + 3 #J, as our pose tangent.
//
// FK: mj_kinematics (every body's and site's world frame). FK plus Jacobian:
// mj_kinematics, mj_comPos (the dof motions cdof that MuJoCo's Jacobians read), then
// mj_jacSite for every marker into one row-major 3 #markers x nv buffer.
#ifndef MOCAPSOLVE_BENCH_PEERS_MUJOCO_MODEL_H_
#define MOCAPSOLVE_BENCH_PEERS_MUJOCO_MODEL_H_

#include <memory>

#include "bench/peers/peer_model.h"

namespace mocapsolve::peers {

Status MakeMujocoModel(const Skeleton& skeleton, const MarkerSet& markers, std::unique_ptr<PeerModel>* model);

}  // namespace mocapsolve::peers

#endif  // MOCAPSOLVE_BENCH_PEERS_MUJOCO_MODEL_H_
