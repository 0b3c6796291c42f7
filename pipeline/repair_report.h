// What a repair did in joint space, as the `repair` and `pipeline` reports and `solve` show it.
#ifndef MOCAPSOLVE_PIPELINE_REPAIR_REPORT_H_
#define MOCAPSOLVE_PIPELINE_REPAIR_REPORT_H_

#include <vector>

#include "io/json_writer.h"
#include "kinematics/skeleton.h"
#include "signal/joint_gap_carry.h"

namespace mocapsolve {

// The joints carried across whole-segment gaps (RepairReport::carried): one
// {"joint", "first_frame", "last_frame", "frames"} per run.
std::vector<JsonObject> CarriedJointsJson(const Skeleton& skeleton, const std::vector<CarriedJointRun>& runs);

// The joints a per-frame solve held at the subject's mean pose as hidden joints
// (SequenceSolveReport::held_frames: frames per joint): {joint: frames} for those held at all.
JsonObject HeldJointsJson(const Skeleton& skeleton, const std::vector<int>& held_frames);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_REPAIR_REPORT_H_
