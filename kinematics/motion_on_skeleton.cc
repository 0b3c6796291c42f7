#include "kinematics/motion_on_skeleton.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace mocapsolve {

Status MotionOnSkeleton(const Skeleton& from, const Motion& motion, const Skeleton& to, Motion* out) {
  const int n = to.num_joints();
  if (from.num_joints() != n) {
    return Status::Error("its skeleton has " + std::to_string(from.num_joints()) + " joints, the subject's " +
                         std::to_string(n));
  }
  const double scale = from.unit().known() && to.unit().known()
                           ? from.unit().metres_per_unit / to.unit().metres_per_unit : 1.0;
  double largest = 0.0;
  for (int j = 0; j < n; ++j) largest = std::max(largest, to.offset(j).norm());
  const double tolerance = 1e-5 * std::max(largest, 1e-12);
  for (int j = 0; j < n; ++j) {
    const std::string joint = "joint " + std::to_string(j) + " '" + to.name(j) + "'";
    if (from.name(j) != to.name(j)) return Status::Error(joint + " is '" + from.name(j) + "' in the motion");
    if (from.parent(j) != to.parent(j)) return Status::Error(joint + ": another parent in the motion");
    const double difference = (scale * from.offset(j) - to.offset(j)).norm();
    if (!(difference <= tolerance)) {
      return Status::Error(joint + ": offset differs by " + std::to_string(difference) + " " + to.unit().name +
                           ": a motion of another skeleton");
    }
  }
  Motion result;
  result.frame_rate = motion.frame_rate;
  result.frames.reserve(motion.frames.size());
  for (const Pose& pose : motion.frames) {
    if (static_cast<int>(pose.rotations.size()) != n || static_cast<int>(pose.translations.size()) != n) {
      return Status::Error("a pose has the wrong joint count");
    }
    Pose converted;
    converted.translations.resize(n);
    converted.rotations.resize(n);
    for (int j = 0; j < n; ++j) {
      converted.translations[j] = scale * pose.translations[j];
      converted.rotations[j] = (to.rest_rotation(j).conjugate() * from.rest_rotation(j) * pose.rotations[j]).normalized();
    }
    result.frames.push_back(std::move(converted));
  }
  MakeSignContinuous(&result);
  *out = std::move(result);
  return Status::Ok();
}

}  // namespace mocapsolve
