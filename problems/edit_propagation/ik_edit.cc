#include "problems/edit_propagation/ik_edit.h"

#include <algorithm>
#include <string>

#include "kinematics/forward_kinematics.h"
#include "kinematics/marker_set.h"

namespace mocapsolve {

Status SolveIkEdit(const Skeleton& skeleton, const Motion& motion, int frame,
                   const std::vector<IkTarget>& targets, const MarkerSolveOptions& options,
                   PoseEdit* edit, IkEditReport* report) {
  if (frame < 0 || frame >= motion.num_frames()) {
    return Status::Error("IK frame " + std::to_string(frame) + " is outside the motion's " +
                         std::to_string(motion.num_frames()) + " frames");
  }
  if (targets.empty()) return Status::Error("IK edit without targets");
  std::vector<MarkerSpec> specs;
  std::vector<Eigen::Vector3d> observed;
  for (const IkTarget& target : targets) {
    if (target.joint < 0 || target.joint >= skeleton.num_joints()) {
      return Status::Error("IK target joint index " + std::to_string(target.joint) + " out of range");
    }
    if (!target.position.allFinite()) return Status::Error("IK target position is not finite");
    specs.push_back({skeleton.name(target.joint), {MarkerAttachment{target.joint, 1.0, Eigen::Vector3d::Zero()}}});
    observed.push_back(target.position);
  }
  MarkerSet markers;
  Status status = MarkerSet::Create(skeleton, specs, &markers);
  if (!status.ok()) return Status::Error("IK targets: " + status.message());
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("IK solver options: " + error);

  PoseEdit result;
  result.frame = frame;
  result.edited = motion.frames[frame];
  IkEditReport local;
  MarkerFrameSolver solver(skeleton, markers, options);
  status = solver.Solve(observed, &result.edited, &local.solve);
  if (!status.ok()) return Status::Error("IK solve at frame " + std::to_string(frame) + ": " + status.message());
  FkData fk(skeleton);
  ForwardKinematics(skeleton, result.edited, &fk);
  for (const IkTarget& target : targets) {
    local.max_target_error =
        std::max(local.max_target_error, (fk.world_positions[target.joint] - target.position).norm());
  }
  *edit = std::move(result);
  if (report != nullptr) *report = local;
  return Status::Ok();
}

}  // namespace mocapsolve
