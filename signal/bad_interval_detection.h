// DetectBad (thesis Algorithm 2): where a naive kinematic solution Y departs from a
// robust reference Y^, and which marker samples that condemns.
//
//   J[f][j] = |p_j(Y_f) - p_j(Y^_f)| > dp_max  or  angle(R_j(Y_f), R_j(Y^_f)) > dr_max
//   M[f][m] = any joint j with w_mj > 0 has J[f][j]                      (M = J w^)
// with p_j, R_j the global joint positions and rotations (FK). The thesis' pseudocode
// shows only the position test; its text applies both, as here.
#ifndef MOCAPSOLVE_SIGNAL_BAD_INTERVAL_DETECTION_H_
#define MOCAPSOLVE_SIGNAL_BAD_INTERVAL_DETECTION_H_

#include <vector>

#include "kinematics/compact_motion.h"
#include "kinematics/marker_set.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"

namespace mocapsolve {

struct BadJointThresholds {
  double position = 0.0;      // dp_max, skeleton length units.
  double rotation_rad = 0.0;  // dr_max.
};

// J as frames x joints (row-major, 1 = bad). Both motions must have the same frames.
Status DetectBadJoints(const Skeleton& skeleton, const Motion& naive, const Motion& reference,
                       const BadJointThresholds& thresholds, std::vector<std::vector<char>>* bad_joints);
// The same with the naive solve kept compact (kinematics/compact_motion.h), read frame by
// frame.
Status DetectBadJoints(const Skeleton& skeleton, const CompactMotion& naive, const Motion& reference,
                       const BadJointThresholds& thresholds, std::vector<std::vector<char>>* bad_joints);

// M as frames x markers: a marker sample is bad when any joint it rides on is bad.
std::vector<std::vector<char>> BadMarkerSamples(const MarkerSet& markers,
                                                const std::vector<std::vector<char>>& bad_joints);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_BAD_INTERVAL_DETECTION_H_
