// `solve` as one function: joint angles from a take's markers, per frame (warm-started,
// problems/marker_solve/sequence_solver.h) and with mode=clip refined as one problem
// (problems/marker_solve/marker_clip_solver.h), the subject's mean pose as the rest prior's
// reference. The CLI (apps/solve_command.cc: flags, BVH, plots) and Python's solve() both
// call it.
#ifndef MOCAPSOLVE_TASKS_SOLVE_TASK_H_
#define MOCAPSOLVE_TASKS_SOLVE_TASK_H_

#include <functional>
#include <string>

#include "io/json_writer.h"
#include "kinematics/motion.h"
#include "kinematics/status.h"
#include "pipeline/subject.h"
#include "problems/marker_solve/marker_clip_solver.h"
#include "problems/marker_solve/sequence_solver.h"
#include "problems/marker_solve/solver_agreement.h"
#include "settings/solver_agreement_settings.h"
#include "settings/memory_settings.h"
#include "settings/solver_settings.h"

namespace mocapsolve {

struct SolveConfig {
  SolverSettings solver;
  int max_frames = 0;  // Solve only the first N frames (0 = all).
  SolverAgreementSettings agreement;  // compare_solvers: both per-frame solvers, compared.
  MemorySettings memory;     // mode=clip: refused before any solve when its estimate is over memory_mb.
};

struct SolveProgress {
  std::function<void(int frames_done)> frames;  // During the per-frame solve.
  // After it (before the clip solve with mode=clip): its report, skeleton units.
  std::function<void(const SequenceSolveReport&)> per_frame_done;
};

struct SolveResult {
  int frames = 0;          // Solved: the take's, or max_frames.
  Motion motion;           // On the take's skeleton, at the file's frame rate.
  SequenceSolveReport per_frame;  // Skeleton units.
  ClipSolveReport clip;           // mode=clip.
  SolverAgreementReport agreement;  // compare_solvers.
  // What --report records: the residuals in mm (residual_unit; skeleton units when the
  // skeleton's unit is unknown), seconds.
  JsonObject report;
};

// Errors: invalid options (naming the option), or a take that cannot be solved (naming
// take.name).
// "lclavicle 120, rclavicle 4": the joints a per-frame solve held at the subject's mean pose
// as hidden joints (SequenceSolveReport::held_frames) and in how many frames, then
// "; about the line to their one seen marker only: lfoot 12" for twist_held_frames; "" if none.
std::string HeldJointsText(const Skeleton& skeleton, const SequenceSolveReport& sequence);

Status RunSolve(const MarkerTake& take, const SolveConfig& config, const SolveProgress& progress,
                SolveResult* result);

// The console lines of a solve, residuals in mm (skeleton units when its unit is unknown):
// the per-frame solve's (frames, time, iterations, RMS, unsolved frames; then the joints
// HeldJointsText names, when any), printed as soon as it is done, ...
std::string PerFrameSolveText(const Skeleton& skeleton, const std::string& solver,
                              const SequenceSolveReport& sequence);
// ... and after the whole solve: both solvers' agreement (compare_solvers) and the clip
// solve's (mode=clip); "" when neither ran.
std::string SolveSummaryText(const Skeleton& skeleton, const SolveConfig& config, const SolveResult& result);

// The motion's marker residual frame by frame (the first `frames` of the take), as CSV:
// frame, time (s), markers observed, RMS and max residual (mm, or skeleton units).
std::string FrameResidualsCsv(const MarkerTake& take, int frames, const Motion& motion);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_TASKS_SOLVE_TASK_H_
