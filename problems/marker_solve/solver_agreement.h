// Solver agreement: does the per-frame solve end at the same cost whichever solver
// minimizes it? The take is solved twice by SolveSequence, with options.solver = kDls and
// then kCeres and every other option the same (the same first-frame search, each frame
// warm-started from the solver's own previous solution, the same residual blocks and
// stopping rules), and the final costs (1/2 sum of squared marker and prior residuals, as
// FrameSolveReport::final_cost) are compared frame by frame:
//   agree(f)  <=>  |c_dls(f) - c_ceres(f)| <= tolerance * max(c_dls(f), c_ceres(f)).
// A frame one solver leaves unsolved and the other not counts as differing; one neither
// solves is skipped. Two solvers that step differently can still part ways where the cost
// has several basins; a frame that differs names where to look.
#ifndef MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SOLVER_AGREEMENT_H_
#define MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SOLVER_AGREEMENT_H_

#include <vector>

#include "problems/marker_solve/sequence_solver.h"

namespace mocapsolve {

struct SolverAgreementFrame {
  int frame = 0;
  double dls_cost = 0.0, ceres_cost = 0.0;  // NaN where unsolved.
  double relative = 0.0;                    // |difference| / max; 1 where one is unsolved.
  double dls_rms = 0.0, ceres_rms = 0.0;    // RMS marker residual, skeleton units.
};

struct SolverAgreementReport {
  double tolerance = 0.01;
  int frames_compared = 0;
  int frames_within = 0;
  double fraction_within = 0.0;
  std::vector<SolverAgreementFrame> worst;  // Largest relative difference first (up to max_listed, > tolerance only).
  std::vector<double> relative;             // Per frame (NaN where skipped).
  SequenceSolveReport dls, ceres;           // Each solver's own sequence report (seconds, RMS).
};

// `options` as for SolveSequence (its solver field is overridden).
Status CompareSolvers(const Skeleton& skeleton, const MarkerSet& markers,
                      const std::vector<std::vector<Eigen::Vector3d>>& observed,
                      const MarkerSolveOptions& options, const Pose& initial, double tolerance,
                      int max_listed, SolverAgreementReport* report);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PROBLEMS_MARKER_SOLVE_SOLVER_AGREEMENT_H_
