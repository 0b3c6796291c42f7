// PeerModel: one established kinematics library (Orocos KDL, MuJoCo, DART) holding the
// same skeleton and markers as ours, so the peers benchmark (bench/peers/peers_main.cc)
// times the same work in each: FK of every joint, FK plus the full positional Jacobian of
// every marker, and (where the library has one) per-frame marker IK.
//
// The model is built from our Skeleton and MarkerSet: a free root (3 translations + 3
// rotation dofs) and a 3-dof rotation at every other joint, placed at
// world_from_joint_j = world_from_joint_parent * T(offset_j) * R_rest_j * R_j exactly as
// kinematics/forward_kinematics.h (constant translations: a joint whose pose animates
// its translation other than the root is refused). Each marker (one attachment, weight 1)
// is a point fixed in its joint's frame (KDL: an end segment on a fixed joint; MuJoCo: a
// site; DART: an end effector). Each adapter states in its own header how a ball joint
// becomes its library's coordinates (KDL: three revolute joints about x, y, z; MuJoCo: a
// ball joint, quaternion w x y z; DART: BallJoint, rotation vector).
//
// Layout of the Jacobian: 3 #markers rows (marker m at rows 3m..3m+2, world frame) by the
// library's own velocity coordinates (#dofs = 3 + 3 #J for each of them), so the sizes
// agree with ours while the column conventions differ.
//
// Workspaces live inside each adapter (allocated at construction); a model is used by one
// thread.
#ifndef MOCAPSOLVE_BENCH_PEERS_PEER_MODEL_H_
#define MOCAPSOLVE_BENCH_PEERS_PEER_MODEL_H_

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve::peers {

// Per-frame IK stopping rule shared by every solver that can take one: stop once the RMS
// marker residual (skeleton units) is at most `target_rms`, or after `max_iterations`.
struct IkTarget {
  double target_rms = 0.0;
  int max_iterations = 100;
};

struct IkResult {
  int iterations = 0;
  double rms = 0.0;        // Reached, skeleton units.
  bool reached = false;    // rms <= target_rms.
};

class PeerModel {
 public:
  virtual ~PeerModel() = default;
  virtual std::string name() const = 0;
  // What the model is, for the report (how ball joints and markers were built).
  virtual std::string description() const = 0;

  // Converts our pose into the library's coordinates and stores them as its current
  // state (not timed: a user of the library would hold its coordinates already).
  virtual void SetPose(const Pose& pose) = 0;
  // The library's coordinates as a vector, and back (for the benchmark's per-frame state:
  // all frames are converted once, untimed, and copied in before each timed call).
  virtual void GetCoordinates(Eigen::VectorXd* q) const = 0;
  virtual void SetCoordinates(const Eigen::VectorXd& q) = 0;
  // Timed: the world frame of every joint (and marker) at the current coordinates.
  virtual void ForwardKinematics() = 0;
  // Timed: FK plus the 3 #markers x #dofs positional Jacobian of every marker.
  virtual void FkAndJacobian() = 0;
  virtual const Eigen::MatrixXd& jacobian() const = 0;
  // After ForwardKinematics: world joint origins (#J) and marker positions (#markers).
  virtual void JointPositions(std::vector<Eigen::Vector3d>* out) = 0;
  virtual void MarkerPositions(std::vector<Eigen::Vector3d>* out) = 0;

  // Per-frame marker IK from the current coordinates (the warm start), which receive the
  // solution. observed[m] in skeleton units. Models without IK return an error.
  virtual bool has_ik() const { return false; }
  virtual Status SolveIk(const std::vector<Eigen::Vector3d>& observed, const IkTarget& target,
                         IkResult* result) {
    (void)observed, (void)target, (void)result;
    return Status::Error(name() + " has no inverse kinematics");
  }
};

// Refuses what the peers cannot hold alike: a non-root joint with animated translation,
// a marker with more than one attachment.
Status CheckPeerCompatible(const Skeleton& skeleton, const MarkerSet& markers);

// The adapters present in this build (each compiled when its library was found).
std::vector<std::string> AvailablePeers();
// Builds the named peer ("kdl", "mujoco", "dart") from our skeleton and markers; the
// skeleton and markers must outlive it.
Status MakePeerModel(const std::string& name, const Skeleton& skeleton, const MarkerSet& markers,
                     std::unique_ptr<PeerModel>* model);

// RMS of |x_m - observed_m| over markers, skeleton units.
double MarkerRms(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& observed);

}  // namespace mocapsolve::peers

#endif  // MOCAPSOLVE_BENCH_PEERS_PEER_MODEL_H_
