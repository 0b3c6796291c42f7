#include "problems/edit_propagation/harmonic_falloff.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/problem.h>
#include <ceres/solver.h>
#include <glog/logging.h>

#include "problems/edit_propagation/harmonic_residual.h"
#include "problems/edit_propagation/pose_kernel.h"

namespace mocapsolve {

std::vector<WeightedEdge> PoseGraphEdges(const Eigen::MatrixXd& features, int knn, double sigma) {
  CHECK_GT(sigma, 0.0);
  CHECK_GE(knn, 1);
  std::vector<WeightedEdge> edges;
  if (features.rows() < 2) return edges;
  const std::vector<std::vector<GraphEdge>> graph = PoseNeighbourGraph(features, knn);
  const double scale = 1.0 / (2.0 * sigma * sigma);
  for (int a = 0; a < static_cast<int>(graph.size()); ++a) {
    for (const GraphEdge& edge : graph[a]) {
      if (edge.neighbour <= a) continue;  // Symmetrized: each edge once.
      edges.push_back({a, edge.neighbour,
                       std::max(1e-300, std::exp(-edge.distance * edge.distance * scale))});
    }
  }
  return edges;
}

bool HarmonicOptions::IsValid(std::string* error) const {
  if (max_iterations < 1) {
    *error = "max_iterations must be >= 1";
    return false;
  }
  if (!(ground_weight >= 0.0) || !std::isfinite(ground_weight)) {
    *error = "ground_weight must be >= 0";
    return false;
  }
  if (num_threads < 1) {
    *error = "num_threads must be >= 1";
    return false;
  }
  if (!ceres::IsSparseLinearAlgebraLibraryTypeAvailable(sparse_library)) {
    *error = std::string("sparse library ") +
             ceres::SparseLinearAlgebraLibraryTypeToString(sparse_library) +
             " is not available in this Ceres build";
    return false;
  }
  return true;
}

Status SolveHarmonicFields(int num_frames, const std::vector<WeightedEdge>& edges,
                           const std::vector<std::vector<std::pair<int, double>>>& labels,
                           const HarmonicOptions& options, std::vector<Eigen::VectorXd>* fields,
                           HarmonicReport* report) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error("harmonic options: " + error);
  if (num_frames < 1) return Status::Error("harmonic falloff: no frames");
  for (const WeightedEdge& edge : edges) {
    if (edge.a < 0 || edge.b < 0 || edge.a >= num_frames || edge.b >= num_frames ||
        edge.a == edge.b || !(edge.kernel >= 0.0) || !std::isfinite(edge.kernel)) {
      return Status::Error("harmonic falloff: bad edge (" + std::to_string(edge.a) + ", " +
                           std::to_string(edge.b) + ")");
    }
  }
  std::vector<bool> labelled(num_frames, false);
  for (const auto& field_labels : labels) {
    if (field_labels.empty()) return Status::Error("harmonic falloff: a field without labels");
    for (const auto& [frame, value] : field_labels) {
      if (frame < 0 || frame >= num_frames || !std::isfinite(value)) {
        return Status::Error("harmonic falloff: bad label at frame " + std::to_string(frame));
      }
      labelled[frame] = true;
    }
  }

  std::vector<double> u(num_frames, 0.0);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (int f = 0; f < num_frames; ++f) problem.AddParameterBlock(&u[f], 1);
  for (const WeightedEdge& edge : edges) {
    if (edge.kernel == 0.0) continue;
    problem.AddResidualBlock(new HarmonicEdgeResidual(edge.kernel), nullptr, &u[edge.a], &u[edge.b]);
  }
  // The ground node: one more frame, always labelled 0, linked to every frame.
  double ground = 0.0;
  if (options.ground_weight > 0.0) {
    problem.AddParameterBlock(&ground, 1);
    problem.SetParameterBlockConstant(&ground);
    for (int f = 0; f < num_frames; ++f) {
      problem.AddResidualBlock(new HarmonicEdgeResidual(options.ground_weight), nullptr, &u[f], &ground);
    }
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.sparse_linear_algebra_library_type = options.sparse_library;
  solver_options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  // Linear least squares: negligible damping makes the first step the exact solution.
  solver_options.initial_trust_region_radius = 1e16;
  solver_options.max_trust_region_radius = 1e32;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-15;
  solver_options.gradient_tolerance = 1e-15;
  solver_options.parameter_tolerance = 1e-15;
  solver_options.num_threads = options.num_threads;
  solver_options.logging_type = ceres::SILENT;

  HarmonicReport local;
  local.frames = num_frames;
  local.edges = static_cast<int>(edges.size());
  fields->assign(labels.size(), Eigen::VectorXd::Zero(num_frames));
  for (size_t k = 0; k < labels.size(); ++k) {
    std::fill(u.begin(), u.end(), 0.0);
    std::vector<bool> fixed(num_frames, false);
    for (const auto& [frame, value] : labels[k]) {
      u[frame] = value;
      fixed[frame] = true;
    }
    for (int f = 0; f < num_frames; ++f) {
      // Every labelled frame of any field is a block whose constancy may change per field.
      if (fixed[f]) {
        problem.SetParameterBlockConstant(&u[f]);
      } else if (labelled[f] && problem.IsParameterBlockConstant(&u[f])) {
        problem.SetParameterBlockVariable(&u[f]);
      }
    }
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options, &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      return Status::Error("harmonic falloff: Ceres failed: " + summary.BriefReport());
    }
    local.iterations += static_cast<int>(summary.iterations.size());
    local.solve_seconds += summary.total_time_in_seconds;
    local.brief = summary.BriefReport();
    for (int f = 0; f < num_frames; ++f) (*fields)[k][f] = u[f];
    // Gradient of E at free frames: sum over edges K (u_i - u_j), the solution's residual.
    std::vector<double> gradient(num_frames, 0.0);
    for (const WeightedEdge& edge : edges) {
      const double g = edge.kernel * (u[edge.a] - u[edge.b]);
      gradient[edge.a] += g;
      gradient[edge.b] -= g;
    }
    for (int f = 0; f < num_frames; ++f) gradient[f] += options.ground_weight * u[f];
    for (int f = 0; f < num_frames; ++f) {
      if (!fixed[f]) local.max_gradient = std::max(local.max_gradient, std::abs(gradient[f]));
    }
  }
  local.fields = static_cast<int>(labels.size());
  if (report != nullptr) *report = local;
  return Status::Ok();
}

Status HarmonicFalloffs(int num_frames, const std::vector<WeightedEdge>& edges,
                        const std::vector<int>& edited_frames, const std::vector<int>& anchors,
                        const HarmonicOptions& options, std::vector<Eigen::VectorXd>* fields,
                        HarmonicReport* report) {
  std::vector<std::vector<std::pair<int, double>>> labels(edited_frames.size());
  for (size_t k = 0; k < edited_frames.size(); ++k) {
    for (size_t other = 0; other < edited_frames.size(); ++other) {
      labels[k].emplace_back(edited_frames[other], other == k ? 1.0 : 0.0);
    }
    for (int anchor : anchors) {
      if (std::find(edited_frames.begin(), edited_frames.end(), anchor) == edited_frames.end()) {
        labels[k].emplace_back(anchor, 0.0);
      }
    }
  }
  return SolveHarmonicFields(num_frames, edges, labels, options, fields, report);
}

}  // namespace mocapsolve
