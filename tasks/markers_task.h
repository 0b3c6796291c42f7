// `markers` as one function: synthetic marker trajectories from a motion and a marker set
// (thesis eq. 9, x_m = MarkerSet::Position after FK), optionally with Gaussian noise, in a
// marker file's unit and axes. The CLI (apps/markers_command.cc) and Python's markers()
// both call it.
#ifndef MOCAPSOLVE_TASKS_MARKERS_TASK_H_
#define MOCAPSOLVE_TASKS_MARKERS_TASK_H_

#include <functional>
#include <string>

#include "io/json_writer.h"
#include "kinematics/marker_set.h"
#include "kinematics/marker_trajectories.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "settings/synthetic_marker_settings.h"

namespace mocapsolve {

struct MarkersConfig {
  std::string markerset;        // A marker set file (.json) or "auto:N[:SEED]" (N markers per bone).
  std::string axes = "x,y,z";   // Marker file axes -> skeleton axes (the file from the model).
  double marker_scale = 0.0;    // Marker file units -> skeleton units; 0: from the units.
  SyntheticMarkerSettings markers;
};

struct MarkersResult {
  MarkerSet marker_set;             // The set used (the auto one, or the file's).
  MarkerTrajectories trajectories;  // In the file's unit and axes, from frame 1.
  double scale = 1.0;               // The marker-to-skeleton scale used.
  std::string warning;              // Non-empty: the skeleton states no unit (markers in its units).
  JsonObject report;
};

// motion_name names the motion in messages. Errors name the option or the file.
Status RunMarkers(const Skeleton& skeleton, const Motion& motion, const std::string& motion_name,
                  const MarkersConfig& config, const std::function<void(int frames_done)>& progress,
                  MarkersResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_MARKERS_TASK_H_
