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

Status SolveClip(const Skeleton& skeleton, const MarkerSet& markers,
                 const std::vector<std::vector<Eigen::Vector3d>>& observed,
                 const ClipSolveOptions& options, Motion* motion, ClipSolveReport* report) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  const int num_frames = static_cast<int>(observed.size());
  if (motion->num_frames() != num_frames) {
    return Status::Error("initial motion has " + std::to_string(motion->num_frames()) +
                         " frames, observations " + std::to_string(num_frames));
  }
  const int nj = skeleton.num_joints();
  const int nm = markers.num_markers();
  std::vector<bool> moves(nj, false);
  for (int m = 0; m < nm; ++m) {
    for (int j : markers.InfluencingJoints(m)) moves[j] = true;
  }
  // Parameter storage: per frame 3 translation + 4 per joint, contiguous.
  const int stride = 3 + 4 * nj;
  std::vector<double> x(static_cast<size_t>(stride) * num_frames);
  auto translation = [&](int f) { return &x[static_cast<size_t>(f) * stride]; };
  auto rotation = [&](int f, int j) { return &x[static_cast<size_t>(f) * stride + 3 + 4 * j]; };
  for (int f = 0; f < num_frames; ++f) {
    Eigen::Map<Eigen::Vector3d>(translation(f)) = motion->frames[f].translations[0];
    for (int j = 0; j < nj; ++j) {
      Eigen::Map<Eigen::Vector4d>(rotation(f, j)) = motion->frames[f].rotations[j].coeffs();
    }
  }

  std::unique_ptr<ceres::LossFunction> loss;
  Status status = MakeLoss(options.loss, options.loss_scale, &loss);
  if (!status.ok()) return status;
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  *report = ClipSolveReport();
  for (int f = 0; f < num_frames; ++f) {
    problem.AddParameterBlock(translation(f), 3);
    report->parameters += 3;
    for (int j = 0; j < nj; ++j) {
      if (!moves[j]) continue;
      ceres::Manifold* manifold = RotationManifold(skeleton.rotation_axes(j));
      problem.AddParameterBlock(rotation(f, j), 4, manifold);
      if (manifold == nullptr) {
        problem.SetParameterBlockConstant(rotation(f, j));
      } else {
        report->parameters += manifold->TangentSize();
      }
    }
  }
  std::vector<double*> blocks;
  for (int f = 0; f < num_frames; ++f) {
    if (static_cast<int>(observed[f].size()) != nm) {
      return Status::Error("frame " + std::to_string(f) + ": observation count differs from the marker set");
    }
    for (int m = 0; m < nm; ++m) {
      if (!observed[f][m].allFinite()) continue;
      auto* residual = new MarkerResidual(&skeleton, &markers, m, &observed[f][m], options.marker_weight);
      blocks.assign(1, translation(f));
      for (int j : residual->joints()) blocks.push_back(rotation(f, j));
      problem.AddResidualBlock(residual, loss.get(), blocks);
      ++report->residual_blocks;
    }
  }
  const int span = static_cast<int>(options.smoothness_order);
  for (int f = 0; f + span < num_frames; ++f) {
    if (options.translation_smoothness > 0.0) {
      blocks.clear();
      for (int k = 0; k <= span; ++k) blocks.push_back(translation(f + k));
      problem.AddResidualBlock(new FiniteDifferenceResidual(options.smoothness_order, false,
                                                            options.translation_smoothness),
                               nullptr, blocks);
      ++report->residual_blocks;
    }
    if (options.rotation_smoothness > 0.0) {
      for (int j = 0; j < nj; ++j) {
        if (!moves[j] || skeleton.num_rotation_dofs(j) == 0) continue;
        blocks.clear();
        for (int k = 0; k <= span; ++k) blocks.push_back(rotation(f + k, j));
        problem.AddResidualBlock(new FiniteDifferenceResidual(options.smoothness_order, true,
                                                              options.rotation_smoothness),
                                 nullptr, blocks);
        ++report->residual_blocks;
      }
    }
  }

  const auto start = std::chrono::steady_clock::now();
  ceres::Solver::Summary summary;
  ceres::Solve(options.ceres, &problem, &summary);
  report->solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report->initial_cost = summary.initial_cost;
  report->final_cost = summary.final_cost;
  report->iterations = static_cast<int>(summary.iterations.size()) - 1;
  report->usable = summary.IsSolutionUsable();
  report->brief = summary.BriefReport();
  report->full = summary.FullReport();
  if (!report->usable) return Status::Error("clip solve failed: " + report->brief);

  double sum = 0.0;
  int count = 0;
  for (int f = 0; f < num_frames; ++f) {
    Pose& pose = motion->frames[f];
    pose.translations[0] = Eigen::Map<const Eigen::Vector3d>(translation(f));
    for (int j = 0; j < nj; ++j) {
      if (moves[j]) pose.rotations[j] = Eigen::Quaterniond(Eigen::Map<const Eigen::Vector4d>(rotation(f, j))).normalized();
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
