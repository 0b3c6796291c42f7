#include "problems/retarget/limb_goals.h"

#include "kinematics/forward_kinematics.h"
#include "problems/retarget/limb_direction_residual.h"
#include "problems/retarget/retarget_quality.h"

namespace mocapsolve {

LimbGoals ComputeLimbGoals(const JointMap& map, const Skeleton& source, const Motion& source_motion,
                           const Skeleton& target, const Pose& target_rest, const RetargetSetup& setup) {
  LimbGoals goals;
  std::vector<MappedLimb> mapped;
  for (const MappedLimb& limb : MappedLimbs(map)) {
    const Eigen::Vector3d local = LimbDirectionInJoint(target, target_rest, limb.target_from, limb.target_to);
    if (local.norm() <= 0.0) continue;
    goals.limbs.push_back({limb.target_from, local});
    goals.names.push_back(limb.limb);
    mapped.push_back(limb);
  }
  const Eigen::Matrix3d turn = setup.target_frame.facing.transpose() * setup.source_frame.facing;
  const int nl = static_cast<int>(mapped.size());
  FkData fk(source);
  for (const Pose& pose : source_motion.frames) {
    ForwardKinematics(source, pose, &fk);
    Eigen::Matrix3Xd directions = Eigen::Matrix3Xd::Zero(3, nl);
    for (int l = 0; l < nl; ++l) {
      const Eigen::Vector3d d = fk.world_positions[mapped[l].source_to] - fk.world_positions[mapped[l].source_from];
      if (d.norm() > 0.0) directions.col(l) = turn * d.normalized();
    }
    goals.directions.push_back(directions);
  }
  return goals;
}

}  // namespace mocapsolve
