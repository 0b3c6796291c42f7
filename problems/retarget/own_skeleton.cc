#include "problems/retarget/own_skeleton.h"

#include <algorithm>

#include <glog/logging.h>

namespace mocapsolve {

bool IsSameSkeleton(const Skeleton& source, const Skeleton& target, const JointMap& map, double* scale) {
  const int ns = source.num_joints(), nt = target.num_joints();
  if (ns != nt || ns == 0 || static_cast<int>(map.target_of_source.size()) != ns ||
      static_cast<int>(map.source_of_target.size()) != nt) {
    return false;
  }
  for (int j = 0; j < ns; ++j) {
    const int t = map.target_of_source[j];
    if (t < 0 || map.source_of_target[t] != j) return false;
    const int p = source.parent(j);
    if ((p < 0) != (target.parent(t) < 0)) return false;
    if (p >= 0 && map.target_of_source[p] != target.parent(t)) return false;
  }
  double dot = 0.0, squares = 0.0, longest = 0.0;
  for (int j = 1; j < ns; ++j) {
    const Eigen::Vector3d& a = source.offset(j);
    const Eigen::Vector3d& b = target.offset(map.target_of_source[j]);
    dot += a.dot(b);
    squares += a.squaredNorm();
    longest = std::max(longest, b.norm());
  }
  if (!(squares > 0.0) || !(dot > 0.0)) return false;
  const double k = dot / squares;
  for (int j = 1; j < ns; ++j) {
    if ((k * source.offset(j) - target.offset(map.target_of_source[j])).norm() > kSameSkeletonTolerance * longest) {
      return false;
    }
  }
  *scale = k;
  return true;
}

Motion TransferOwnMotion(const Skeleton& source, const Motion& source_motion, const Skeleton& target,
                         const JointMap& map, double scale) {
  const int nt = target.num_joints();
  Motion out;
  out.frame_rate = source_motion.frame_rate;
  out.frames.reserve(source_motion.frames.size());
  std::vector<Eigen::Quaterniond> rest_change(nt);  // R_rest_t^-1 R_rest_s.
  for (int t = 0; t < nt; ++t) {
    const int s = map.source_of_target[t];
    CHECK_GE(s, 0) << "TransferOwnMotion: joint " << target.name(t) << " is not mapped";
    rest_change[t] = (target.rest_rotation(t).conjugate() * source.rest_rotation(s)).normalized();
  }
  for (const Pose& pose : source_motion.frames) {
    Pose mapped;
    mapped.rotations.resize(nt);
    mapped.translations.resize(nt);
    for (int t = 0; t < nt; ++t) {
      const int s = map.source_of_target[t];
      mapped.rotations[t] = (rest_change[t] * pose.rotations[s]).normalized();
      mapped.translations[t] = t > 0 && pose.translations[s] == source.offset(s)
                                   ? target.offset(t)
                                   : Eigen::Vector3d(scale * pose.translations[s]);
    }
    out.frames.push_back(std::move(mapped));
  }
  return out;
}

}  // namespace mocapsolve
