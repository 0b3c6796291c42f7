#include "problems/marker_solve/marker_clip_solver.h"

#include <chrono>
#include <cmath>
#include <memory>

#include <ceres/problem.h>

#include "problems/marker_solve/marker_frame_solver.h"
#include "problems/marker_solve/marker_residual.h"
#include "solvers/right_quaternion_manifold.h"

namespace mocapsolve {

bool ClipSolveOptions::IsValid(std::string* error) const {
  if (!(marker_weight > 0.0) || !std::isfinite(marker_weight)) {
    return *error = "marker weight must be positive and finite", false;
  }
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) {
    return *error = "loss scale must be positive and finite", false;
  }
  for (const double w : {rotation_smoothness, translation_smoothness}) {
    if (!(w >= 0.0) || !std::isfinite(w)) {
      return *error = "smoothness weights must be finite and >= 0", false;
    }
  }
  std::unique_ptr<ceres::LossFunction> loss_function;
  const Status status = MakeLoss(loss, loss_scale, &loss_function);
  if (!status.ok()) return *error = status.message(), false;
  if (solver == "dls") {
    if (dls_linear_solver == DlsLinearSolver::kDense) {
      return *error = "clip DLS: the linear solver must be block_banded or sparse_ldlt", false;
    }
    return dls.IsValid(error);
  }
  if (solver != "ceres") return *error = "clip solver: unknown '" + solver + "' (ceres, dls)", false;
  return ceres.IsValid(error);
}

ceres::Solver::Options DefaultClipCeresOptions() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  // Eigen's simplicial LDLT beats CHOLMOD (on Debian's ATLAS) by 2x on these banded
  // systems with velocity smoothing: 01_01's 2752 frames solve in ~8 s instead of 13 s.
  options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  options.max_num_iterations = 50;
  options.function_tolerance = 1e-8;
  options.num_threads = 2;
  options.logging_type = ceres::SILENT;
  return options;
}

DlsOptions DefaultClipDlsOptions() {
  DlsOptions options;
  options.max_iterations = 50;
  options.function_tolerance = 1e-8;
  return options;
}

void ClipProblem::AddTo(ceres::Problem* problem) const {
  for (const Parameter& p : parameters) {
    problem->AddParameterBlock(p.values, p.size, p.manifold);
    if (p.constant) problem->SetParameterBlockConstant(p.values);
  }
  std::vector<double*> blocks;
  for (const Residual& r : residuals) {
    blocks.clear();
    for (int b : r.blocks) blocks.push_back(parameters[b].values);
    problem->AddResidualBlock(r.cost.get(), r.robust ? loss.get() : nullptr, blocks);
  }
}

void ClipProblem::AddTo(DlsProblem* problem) const {
  for (const Parameter& p : parameters) {
    const int index = problem->AddParameterBlock(p.values, p.size, p.manifold);
    if (p.constant) problem->SetParameterBlockConstant(index);
  }
  for (const Residual& r : residuals) {
    problem->AddResidualBlock(r.cost.get(), r.robust ? loss.get() : nullptr, r.blocks);
  }
}

Status BuildClipProblem(const Skeleton& skeleton, const MarkerSet& markers,
                        const std::vector<std::vector<Eigen::Vector3d>>& observed,
                        const ClipSolveOptions& options, const Motion& initial, ClipProblem* problem) {
  const int num_frames = static_cast<int>(observed.size());
  if (initial.num_frames() != num_frames) {
    return Status::Error("initial motion has " + std::to_string(initial.num_frames()) +
                         " frames, observations " + std::to_string(num_frames));
  }
  const int nj = skeleton.num_joints();
  const int nm = markers.num_markers();
  for (int f = 0; f < num_frames; ++f) {
    if (static_cast<int>(observed[f].size()) != nm) {
      return Status::Error("frame " + std::to_string(f) + ": observation count differs from the marker set");
    }
  }
  ClipProblem& p = *problem;
  p.moves.assign(nj, false);
  for (int m = 0; m < nm; ++m) {
    for (int j : markers.InfluencingJoints(m)) p.moves[j] = true;
  }
  const std::vector<bool>& moves = p.moves;
  Status status = MakeLoss(options.loss, options.loss_scale, &p.loss);
  if (!status.ok()) return status;
  // Parameter storage: per frame 3 translation + 4 per joint, contiguous.
  p.stride = 3 + 4 * nj;
  p.x.assign(static_cast<size_t>(p.stride) * num_frames, 0.0);
  auto translation = [&](int f) { return &p.x[static_cast<size_t>(f) * p.stride]; };
  auto rotation = [&](int f, int j) { return &p.x[static_cast<size_t>(f) * p.stride + 3 + 4 * j]; };
  p.parameters.clear();
  p.residuals.clear();
  p.frame_columns = 0;
  // Block index of (frame, joint) (-1: not a block) and of the frame's translation.
  std::vector<int> joint_block(nj, -1);
  int blocks_per_frame = 1;
  for (int j = 0; j < nj; ++j) {
    if (moves[j]) joint_block[j] = blocks_per_frame++;
  }
  for (int f = 0; f < num_frames; ++f) {
    Eigen::Map<Eigen::Vector3d>(translation(f)) = initial.frames[f].translations[0];
    for (int j = 0; j < nj; ++j) {
      Eigen::Map<Eigen::Vector4d>(rotation(f, j)) = initial.frames[f].rotations[j].coeffs();
    }
    p.parameters.push_back({translation(f), 3, nullptr, false});
    if (f == 0) p.frame_columns += 3;
    for (int j = 0; j < nj; ++j) {
      if (!moves[j]) continue;
      ceres::Manifold* manifold = RotationManifold(skeleton.rotation_axes(j));
      p.parameters.push_back({rotation(f, j), 4, manifold, manifold == nullptr});
      if (f == 0 && manifold != nullptr) p.frame_columns += manifold->TangentSize();
    }
  }
  for (int f = 0; f < num_frames; ++f) {
    for (int m = 0; m < nm; ++m) {
      if (!observed[f][m].allFinite()) continue;
      auto residual = std::make_unique<MarkerResidual>(
          &skeleton, &markers, m, &observed[f][m], options.marker_weight * std::sqrt(markers.marker(m).solve_weight));
      std::vector<int> blocks(1, f * blocks_per_frame);
      for (int j : residual->joints()) blocks.push_back(f * blocks_per_frame + joint_block[j]);
      p.residuals.push_back({std::move(residual), true, std::move(blocks)});
    }
  }
  const int span = static_cast<int>(options.smoothness_order);
  for (int f = 0; f + span < num_frames; ++f) {
    if (options.translation_smoothness > 0.0) {
      std::vector<int> blocks;
      for (int k = 0; k <= span; ++k) blocks.push_back((f + k) * blocks_per_frame);
      p.residuals.push_back({std::make_unique<FiniteDifferenceResidual>(options.smoothness_order, false,
                                                                        options.translation_smoothness),
                             false, std::move(blocks)});
    }
    if (options.rotation_smoothness > 0.0) {
      for (int j = 0; j < nj; ++j) {
        if (!moves[j] || skeleton.num_rotation_dofs(j) == 0) continue;
        std::vector<int> blocks;
        for (int k = 0; k <= span; ++k) blocks.push_back((f + k) * blocks_per_frame + joint_block[j]);
        p.residuals.push_back({std::make_unique<FiniteDifferenceResidual>(options.smoothness_order, true,
                                                                          options.rotation_smoothness),
                               false, std::move(blocks)});
      }
    }
  }
  return Status::Ok();
}

Status SolveClip(const Skeleton& skeleton, const MarkerSet& markers,
                 const std::vector<std::vector<Eigen::Vector3d>>& observed,
                 const ClipSolveOptions& options, Motion* motion, ClipSolveReport* report) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  ClipProblem problem;
  Status status = BuildClipProblem(skeleton, markers, observed, options, *motion, &problem);
  if (!status.ok()) return status;
  const int num_frames = static_cast<int>(observed.size());
  const int nj = skeleton.num_joints();
  *report = ClipSolveReport();
  report->solver = options.solver;
  report->residual_blocks = static_cast<int>(problem.residuals.size());
  report->parameters = problem.frame_columns * num_frames;

  const auto start = std::chrono::steady_clock::now();
  if (options.solver == "ceres") {
    ceres::Problem::Options problem_options;
    problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem ceres_problem(problem_options);
    problem.AddTo(&ceres_problem);
    ceres::Solver::Summary summary;
    ceres::Solve(options.ceres, &ceres_problem, &summary);
    report->initial_cost = summary.initial_cost;
    report->final_cost = summary.final_cost;
    report->iterations = static_cast<int>(summary.iterations.size()) - 1;
    report->usable = summary.IsSolutionUsable();
    report->brief = summary.BriefReport();
    report->full = summary.FullReport();
    report->linear_solve_seconds = summary.linear_solver_time_in_seconds;
  } else {
    DlsProblem dls_problem;
    problem.AddTo(&dls_problem);
    DlsSolver solver(options.dls_linear_solver, problem.frame_columns);
    DlsSummary summary;
    solver.Solve(options.dls, &dls_problem, &summary);
    report->initial_cost = summary.initial_cost;
    report->final_cost = summary.final_cost;
    report->iterations = summary.iterations;
    report->usable = summary.IsSolutionUsable();
    report->brief = summary.BriefReport();
    report->full = report->brief;
    report->factorization_flops = solver.BandFactorizationFlops();
    report->linear_solve_seconds = solver.linear_solve_seconds();
  }
  report->solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!report->usable) return Status::Error("clip solve failed: " + report->brief);

  double sum = 0.0;
  int count = 0;
  for (int f = 0; f < num_frames; ++f) {
    Pose& pose = motion->frames[f];
    const double* frame = &problem.x[static_cast<size_t>(f) * problem.stride];
    pose.translations[0] = Eigen::Map<const Eigen::Vector3d>(frame);
    for (int j = 0; j < nj; ++j) {
      if (problem.moves[j]) pose.rotations[j] = Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(frame + 3 + 4 * j)).normalized();
    }
    int n = 0;
    const double rms = RmsMarkerError(skeleton, markers, pose, observed[f], &n);
    sum += rms * rms * n;
    count += n;
  }
  report->rms_marker_error = count > 0 ? std::sqrt(sum / count) : 0.0;
  MakeSignContinuous(motion);
  return Status::Ok();
}

}  // namespace mocapsolve
