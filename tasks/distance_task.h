// `distance` as one function: the pose-space distance and falloff of an edit at one frame
// (Dean, Lewis & Chalmers 2018; problems/edit_propagation/falloff.h) by one or more methods
// (green, diffusion, isomap) and a sweep of Green's-function sigmas, with the figures that
// judge them (problems/edit_propagation/falloff_analysis.h: the clip's period, the weight at
// the same and opposite phase of other cycles, the second difference at the edit, where the
// weight ends). The CLI (apps/distance_command.cc: CSV, SVG, console) and Python's distance()
// both call it.
#ifndef MOCAPSOLVE_TASKS_DISTANCE_TASK_H_
#define MOCAPSOLVE_TASKS_DISTANCE_TASK_H_

#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "problems/edit_propagation/falloff.h"
#include "settings/falloff_settings.h"

namespace mocapsolve {

struct DistanceConfig {
  int frame = -1;                   // The edited frame (0-based), required.
  std::string methods = "green";    // green | diffusion | isomap, comma-separated.
  FalloffSettings falloff;
};

// One weight curve's figures (frames; -1: never; NaN where not defined).
struct FalloffFigures {
  std::string name;          // The method, or "sigma S" of the sweep.
  double ms = 0.0;           // Its own time (methods only).
  double second_difference = 0.0, kink_ratio = 0.0, slope_before = 0.0, slope_after = 0.0;
  int end_before_05 = -1, end_after_05 = -1, end_before_005 = -1, end_after_005 = -1;
  double min_same_phase_weight = 1.0, max_opposite_phase_weight = 0.0;  // Over the other cycles.
};

struct DistanceResult {
  int frames = 0, frame = 0, region_begin = 0, region_end = 0;
  std::vector<Falloff> methods;        // One per method, in the order given.
  std::vector<std::string> method_names;
  std::vector<double> sweep;           // The sigmas, and their Green's falloffs:
  std::vector<Falloff> swept;
  std::vector<FalloffFigures> method_figures, sweep_figures;
  int period = 0;                      // Of the clip in frames (0: not periodic).
  std::vector<int> same_phase, opposite_phase;
  bool spectral = false;               // A Green's function was built (green, diffusion, sweep).
  double sigma_used = 0.0;
  int eigenpairs_used = 0;
  bool sparse_kernel = false;
  double features_ms = 0.0, build_ms = 0.0;
  std::string csv;                     // frame,distance,weight of the first method, the others'
                                       // distances, the sweep's weights (what --out writes).
  JsonObject report;
};

// Errors name the option (--method, --sweep, --frame, --region, the falloff's) or the motion.
Status RunDistance(const Skeleton& skeleton, const Motion& motion, const std::string& motion_name,
                   const DistanceConfig& config, DistanceResult* result);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_DISTANCE_TASK_H_
