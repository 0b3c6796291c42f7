// `propagate` as one function (Dean, Lewis & Chalmers 2018, eqs. 4-5;
// problems/edit_propagation/): the edit of one or more frames (an edit file, or an IK solve
// moving joints to points) carried to every frame of the region with a falloff (green,
// harmonic or spline; pipeline/edit_weights.h), the feet planted in the source measured
// and, with keep_contacts, held. The CLI (apps/propagate_command.cc) and Python's
// propagate(skeleton, motion, edit=... | ik_target=...) both call it.
#ifndef MOCAPSOLVE_TASKS_PROPAGATE_TASK_H_
#define MOCAPSOLVE_TASKS_PROPAGATE_TASK_H_

#include <functional>
#include <string>
#include <vector>

#include "io/json_writer.h"
#include "kinematics/motion.h"
#include "kinematics/skeleton.h"
#include "kinematics/status.h"
#include "pipeline/edit_weights.h"
#include "settings/falloff_settings.h"
#include "settings/memory_settings.h"
#include "settings/propagate_settings.h"
#include "settings/solver_settings.h"
#include "viewer/view_scene.h"

namespace mocapsolve {

struct PropagateConfig {
  std::string edit;          // An edit file (.json, io/edit_file.h); or
  std::string ik_target;     // JOINT:x,y,z[;...] (world, skeleton units) at `frame`.
  int frame = -1;            // Required with ik_target; with edit, checked against a one-edit file (-1: not given).
  std::string method = "green";  // green | harmonic | spline.
  std::string foot_joints;   // Comma-separated; "" = names with foot, toe or ankle.
  PropagateSettings propagate;
  FalloffSettings falloff;
  SolverSettings solver;     // The IK solve's; sparse_library: the harmonic solve's.
  MemorySettings memory;     // green (or compared with it): refused before any work over memory_mb.
};

struct FalloffComparison {
  std::string method;
  double correlation = 0.0, max_difference = 0.0;
};

struct PropagateResult {
  Motion propagated;
  std::vector<int> frames;            // The edited frames.
  int region_begin = 0, region_end = 0;
  EditWeights weights;                // One (frames,) field per edit.
  bool ik = false;
  IkEditReport ik_report;             // Skeleton units.
  std::vector<FalloffComparison> comparisons;  // compare_falloffs.
  bool contacts_found = false;        // Foot contacts detected (drift measured).
  int contact_frames = 0;
  double drift_cm_before = 0.0, drift_cm_after = 0.0;  // after: with keep_contacts.
  bool unit_assumed = false;          // The skeleton's unit unknown: cm assumed.
  JsonObject report;                  // What --report records.
};

// Errors name the option or the edit file's entry. contact_progress (optional): frames of
// the contact re-solve done, and the total.
Status RunPropagate(const Skeleton& skeleton, const Motion& motion, const PropagateConfig& config,
                    const std::function<void(int done, int total)>& contact_progress, PropagateResult* result);

// The console lines after RunPropagate: the IK solve, the falloff comparisons, the feet.
std::string PropagateSummary(const PropagateConfig& config, const PropagateResult& result);

// The falloff weights as CSV: frame,weight (one weight_<frame> column per edit when several).
std::string FalloffWeightsCsv(const PropagateResult& result);

// The page of `propagate --view`: the propagated clip over the original (ghosted), and each
// edit's falloff as a curve. `motion_name` names the clip (its file) in the title.
Status MakePropagateViewScene(const std::string& motion_name, const Skeleton& skeleton, const Motion& motion,
                              const PropagateResult& result, ViewScene* scene);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_PROPAGATE_TASK_H_
