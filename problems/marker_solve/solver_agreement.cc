#include "problems/marker_solve/solver_agreement.h"

#include <algorithm>
#include <cmath>

namespace mocapsolve {

Status CompareSolvers(const Skeleton& skeleton, const MarkerSet& markers,
                      const std::vector<std::vector<Eigen::Vector3d>>& observed,
                      const MarkerSolveOptions& options, const Pose& initial, double tolerance,
                      int max_listed, SolverAgreementReport* report) {
  *report = SolverAgreementReport();
  report->tolerance = tolerance;
  if (!(tolerance >= 0.0)) return Status::Error("the agreement tolerance must be >= 0");
  Motion motion;
  MarkerSolveOptions each = options;
  each.solver = SolverKind::kDls;
  Status status = SolveSequence(skeleton, markers, observed, each, initial, &motion, &report->dls);
  if (!status.ok()) return status;
  each.solver = SolverKind::kCeres;
  status = SolveSequence(skeleton, markers, observed, each, initial, &motion, &report->ceres);
  if (!status.ok()) return status;
  const int frames = static_cast<int>(observed.size());
  report->relative.assign(frames, std::nan(""));
  std::vector<SolverAgreementFrame> differing;
  for (int f = 0; f < frames; ++f) {
    SolverAgreementFrame frame;
    frame.frame = f;
    frame.dls_cost = report->dls.frame_cost[f];
    frame.ceres_cost = report->ceres.frame_cost[f];
    frame.dls_rms = report->dls.frame_rms[f];
    frame.ceres_rms = report->ceres.frame_rms[f];
    const bool dls_solved = std::isfinite(frame.dls_cost), ceres_solved = std::isfinite(frame.ceres_cost);
    if (!dls_solved && !ceres_solved) continue;
    ++report->frames_compared;
    if (dls_solved != ceres_solved) {
      frame.relative = 1.0;
    } else {
      const double larger = std::max(frame.dls_cost, frame.ceres_cost);
      frame.relative = larger > 0.0 ? std::abs(frame.dls_cost - frame.ceres_cost) / larger : 0.0;
    }
    report->relative[f] = frame.relative;
    if (frame.relative <= tolerance) {
      ++report->frames_within;
    } else {
      differing.push_back(frame);
    }
  }
  report->fraction_within =
      report->frames_compared > 0 ? static_cast<double>(report->frames_within) / report->frames_compared : 1.0;
  std::stable_sort(differing.begin(), differing.end(),
                   [](const SolverAgreementFrame& a, const SolverAgreementFrame& b) { return a.relative > b.relative; });
  if (static_cast<int>(differing.size()) > max_listed) differing.resize(std::max(0, max_listed));
  report->worst = std::move(differing);
  return Status::Ok();
}

}  // namespace mocapsolve
