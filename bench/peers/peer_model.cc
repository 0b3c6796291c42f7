#include "bench/peers/peer_model.h"

#include <cmath>

#ifdef MOCAPSOLVE_HAVE_KDL
#include "bench/peers/kdl_tree.h"
#endif
#ifdef MOCAPSOLVE_HAVE_MUJOCO
#include "bench/peers/mujoco_model.h"
#endif
#ifdef MOCAPSOLVE_HAVE_DART
#include "bench/peers/dart_skeleton.h"
#endif

namespace mocapsolve::peers {

Status CheckPeerCompatible(const Skeleton& skeleton, const MarkerSet& markers) {
  for (int j = 1; j < skeleton.num_joints(); ++j) {
    if (skeleton.has_translation_channels(j)) {
      return Status::Error("peers: joint '" + skeleton.name(j) +
                           "' animates its translation; the peer models hold constant offsets");
    }
  }
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (markers.marker(m).attachments.size() != 1) {
      return Status::Error("peers: marker '" + markers.label(m) + "' is blended over several joints");
    }
  }
  return Status::Ok();
}

std::vector<std::string> AvailablePeers() {
  std::vector<std::string> names;
#ifdef MOCAPSOLVE_HAVE_KDL
  names.push_back("kdl");
#endif
#ifdef MOCAPSOLVE_HAVE_MUJOCO
  names.push_back("mujoco");
#endif
#ifdef MOCAPSOLVE_HAVE_DART
  names.push_back("dart");
#endif
  return names;
}

Status MakePeerModel(const std::string& name, const Skeleton& skeleton, const MarkerSet& markers,
                     std::unique_ptr<PeerModel>* model) {
  Status status = CheckPeerCompatible(skeleton, markers);
  if (!status.ok()) return status;
#ifdef MOCAPSOLVE_HAVE_KDL
  if (name == "kdl") {
    *model = MakeKdlTree(skeleton, markers);
    return Status::Ok();
  }
#endif
#ifdef MOCAPSOLVE_HAVE_MUJOCO
  if (name == "mujoco") return MakeMujocoModel(skeleton, markers, model);
#endif
#ifdef MOCAPSOLVE_HAVE_DART
  if (name == "dart") {
    *model = MakeDartSkeleton(skeleton, markers, DartIkSettings());
    return Status::Ok();
  }
#endif
  return Status::Error("peers: '" + name + "' is not built here (install it: scripts/setup.sh --with-peers)");
}

double MarkerRms(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& observed) {
  double sum = 0.0;
  for (size_t m = 0; m < observed.size(); ++m) sum += (positions[m] - observed[m]).squaredNorm();
  return observed.empty() ? 0.0 : std::sqrt(sum / observed.size());
}

}  // namespace mocapsolve::peers
