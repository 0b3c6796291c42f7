#include "problems/edit_propagation/falloff.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glog/logging.h>

#include "problems/edit_propagation/isomap_distance.h"
#include "problems/edit_propagation/pose_kernel.h"

namespace mocapsolve {
namespace {

}  // namespace

bool ParseFalloffMethod(const std::string& text, FalloffMethod* method) {
  if (text == "green") *method = FalloffMethod::kGreen;
  else if (text == "diffusion") *method = FalloffMethod::kDiffusion;
  else if (text == "isomap") *method = FalloffMethod::kIsomap;
  else return false;
  return true;
}

std::string FalloffMethodName(FalloffMethod method) {
  switch (method) {
    case FalloffMethod::kGreen: return "green";
    case FalloffMethod::kDiffusion: return "diffusion";
    case FalloffMethod::kIsomap: return "isomap";
  }
  return "unknown";
}

bool FalloffOptions::IsValid(std::string* error) const {
  if (!(sigma >= 0.0) || !std::isfinite(sigma)) *error = "sigma: expected a finite value >= 0 (0 = auto)";
  else if (!(sigma_scale > 0.0) || !std::isfinite(sigma_scale)) *error = "sigma_scale: expected a finite value > 0";
  else if (eigenpairs < 0) *error = "eigenpairs: expected >= 0 (0 = all terms)";
  else if (region_begin < 0) *error = "region: begin must be >= 0";
  else if (region_end < -1) *error = "region: end must be >= 0 (or -1 for the clip's end)";
  else if (diffusion_steps < 1) *error = "diffusion_steps: expected >= 1";
  else if (knn < 1) *error = "knn: expected >= 1";
  else if (isomap_knn < 1) *error = "isomap_knn: expected >= 1";
  else if (sparse_above_frames < 0) *error = "sparse_above_frames: expected >= 0";
  else if (!(null_eigenvalue >= 0.0) || !(null_eigenvalue < 1.0)) *error = "null_eigenvalue: expected [0, 1)";
  else if (kernel == KernelMode::kSparse && eigenpairs == 0) {
    *error = "eigenpairs: 0 (all terms) needs the dense kernel";
  } else {
    return true;
  }
  return false;
}

Status GreenFunction::Build(const Eigen::MatrixXd& features, const FalloffOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  const int n = static_cast<int>(features.rows());
  if (n < 3) return Status::Error("motion: a falloff needs at least 3 frames, got " + std::to_string(n));
  if (!features.allFinite()) return Status::Error("features: non-finite pose vector");
  sigma_ = options.sigma;
  if (sigma_ == 0.0) {
    sigma_ = options.sigma_scale * MedianStepDistance(features);
    if (!(sigma_ > 0.0)) {
      return Status::Error("sigma: the automatic width is 0 (the median pose step is 0); give sigma");
    }
  }
  sparse_ = options.kernel == KernelMode::kSparse ||
            (options.kernel == KernelMode::kAuto && n > options.sparse_above_frames);
  if (sparse_ && options.eigenpairs == 0) {
    if (options.kernel == KernelMode::kSparse) return Status::Error("eigenpairs: 0 (all terms) needs the dense kernel");
    sparse_ = false;  // kAuto: "all terms" asks for the dense solve.
  }
  Status status = Status::Ok();
  if (sparse_) {
    // m kept terms plus lambda_0 and up to 4 more null-space (island) eigenvalues;
    // Lanczos needs count < n.
    const int count = std::min(options.eigenpairs + 5, n - 1);
    status = SparseLaplacianEigenpairs(SparsePoseKernel(PoseNeighbourGraph(features, options.knn), sigma_),
                                       count, 0, &eigen_);
  } else {
    status = DenseLaplacianEigenpairs(DensePoseKernel(features, sigma_), 0, &eigen_);
  }
  if (!status.ok()) return status;
  degrees_ = eigen_.degrees;
  std::vector<int> kept;
  const int limit = options.eigenpairs == 0 ? n : options.eigenpairs;
  for (int k = 0; k < eigen_.eigenvalues.size() && static_cast<int>(kept.size()) < limit; ++k) {
    if (eigen_.eigenvalues[k] > options.null_eigenvalue) kept.push_back(k);
  }
  if (kept.empty()) return Status::Error("eigenpairs: no nonzero eigenvalue (every frame isolated?); widen sigma");
  const int m = static_cast<int>(kept.size());
  first_kept_ = kept.front();
  vectors_.resize(n, m);
  inverse_eigenvalues_.resize(m);
  for (int c = 0; c < m; ++c) {
    vectors_.col(c) = eigen_.eigenvectors.col(kept[c]);
    inverse_eigenvalues_[c] = 1.0 / eigen_.eigenvalues[kept[c]];
  }
  scaled_vectors_ = vectors_ * inverse_eigenvalues_.asDiagonal();
  return Status::Ok();
}

void GreenFunction::Row(int frame, Eigen::VectorXd* g) const {
  CHECK(frame >= 0 && frame < num_frames());
  g->noalias() = vectors_ * scaled_vectors_.row(frame).transpose();
}

void GreenFunction::Weights(int frame, int region_begin, int region_end, Falloff* falloff) const {
  Eigen::VectorXd g;
  Row(frame, &g);
  FalloffFromSimilarity(g, frame, region_begin, region_end, falloff);
  falloff->sigma_used = sigma_;
  falloff->eigenpairs_used = eigenpairs_used();
  falloff->sparse_used = sparse_;
}

void GreenFunction::DiffusionDistance(int frame, int steps, Eigen::VectorXd* d) const {
  CHECK(frame >= 0 && frame < num_frames());
  CHECK_GE(steps, 1);
  const int m = eigenpairs_used();
  // psi_k(j) = phi_k(j) * sqrt(sum D / D_jj); the term weights mu_k^(2t).
  const Eigen::ArrayXd root = (degrees_.sum() / degrees_.array()).sqrt();
  Eigen::ArrayXd weight(m);
  for (int c = 0; c < m; ++c) {
    const double mu = 1.0 - 1.0 / inverse_eigenvalues_[c];
    weight[c] = std::pow(mu * mu, steps);
  }
  const Eigen::ArrayXd at_frame = vectors_.row(frame).transpose().array() * root[frame];
  d->resize(num_frames());
  for (int j = 0; j < num_frames(); ++j) {
    const Eigen::ArrayXd diff = vectors_.row(j).transpose().array() * root[j] - at_frame;
    (*d)[j] = std::sqrt((weight * diff.square()).sum());
  }
}

Status ResolveRegion(int num_frames, int frame, int region_begin, int region_end, int* begin,
                     int* end) {
  *begin = region_begin;
  *end = region_end < 0 ? num_frames : region_end;
  if (*begin < 0 || *end > num_frames || *begin >= *end) {
    return Status::Error("region: expected 0 <= begin < end <= " + std::to_string(num_frames) +
                         ", got " + std::to_string(region_begin) + ":" + std::to_string(region_end));
  }
  if (frame < *begin || frame >= *end) {
    return Status::Error("frame: " + std::to_string(frame) + " is outside the region " +
                         std::to_string(*begin) + ":" + std::to_string(*end) + " (of " +
                         std::to_string(num_frames) + " frames)");
  }
  return Status::Ok();
}

void FalloffFromSimilarity(const Eigen::VectorXd& similarity, int frame, int region_begin,
                           int region_end, Falloff* falloff) {
  const int n = static_cast<int>(similarity.size());
  CHECK(0 <= region_begin && region_begin <= frame && frame < region_end && region_end <= n);
  falloff->frame = frame;
  falloff->region_begin = region_begin;
  falloff->region_end = region_end;
  falloff->raw = similarity;
  falloff->weight = Eigen::VectorXd::Zero(n);
  const double low = similarity.segment(region_begin, region_end - region_begin).minCoeff();
  const double range = similarity[frame] - low;
  for (int j = region_begin; j < region_end; ++j) {
    // A degenerate row (G_ii is the minimum) leaves the edit at its own frame only.
    const double w = range > 0.0 ? (similarity[j] - low) / range : (j == frame ? 1.0 : 0.0);
    falloff->weight[j] = std::clamp(w, 0.0, 1.0);
  }
  falloff->distance = 1.0 - falloff->weight.array();
}

void FalloffFromDistance(const Eigen::VectorXd& distance, int frame, int region_begin,
                         int region_end, Falloff* falloff) {
  const int n = static_cast<int>(distance.size());
  CHECK(0 <= region_begin && region_begin <= frame && frame < region_end && region_end <= n);
  falloff->frame = frame;
  falloff->region_begin = region_begin;
  falloff->region_end = region_end;
  falloff->raw = distance;
  falloff->distance = Eigen::VectorXd::Ones(n);
  double high = 0.0;
  for (int j = region_begin; j < region_end; ++j) {
    if (std::isfinite(distance[j])) high = std::max(high, distance[j] - distance[frame]);
  }
  for (int j = region_begin; j < region_end; ++j) {
    // Unreachable frames (infinite distance) are as far as can be; a region of identical
    // poses (high = 0) takes the whole edit.
    const double d = !std::isfinite(distance[j]) ? 1.0
                     : high > 0.0                ? (distance[j] - distance[frame]) / high
                                                 : 0.0;
    falloff->distance[j] = std::clamp(d, 0.0, 1.0);
  }
  falloff->weight = 1.0 - falloff->distance.array();
}

Status ComputeFalloffs(const Skeleton& skeleton, const Motion& motion,
                       const std::vector<int>& frames, FalloffMethod method,
                       const FalloffOptions& options, std::vector<Falloff>* falloffs) {
  std::string error;
  if (!options.IsValid(&error)) return Status::Error(error);
  Eigen::MatrixXd features;
  Status status = PoseFeatures(skeleton, motion, options.features, &features);
  if (!status.ok()) return status;
  const int n = static_cast<int>(features.rows());
  int begin = 0, end = 0;
  for (int frame : frames) {
    if (frame < 0 || frame >= n) {
      return Status::Error("frame: " + std::to_string(frame) + " is outside the clip's 0.." +
                           std::to_string(n - 1));
    }
    status = ResolveRegion(n, frame, options.region_begin, options.region_end, &begin, &end);
    if (!status.ok()) return status;
  }
  falloffs->assign(frames.size(), Falloff());
  if (frames.empty()) return Status::Ok();
  if (method == FalloffMethod::kIsomap) {
    const auto graph = PoseNeighbourGraph(features, options.isomap_knn);
    for (size_t e = 0; e < frames.size(); ++e) {
      FalloffFromDistance(GeodesicDistances(graph, frames[e]), frames[e], begin, end, &(*falloffs)[e]);
      (*falloffs)[e].sparse_used = true;
    }
    return Status::Ok();
  }
  GreenFunction green;
  status = green.Build(features, options);
  if (!status.ok()) return status;
  for (size_t e = 0; e < frames.size(); ++e) {
    Falloff* falloff = &(*falloffs)[e];
    if (method == FalloffMethod::kGreen) {
      green.Weights(frames[e], begin, end, falloff);
    } else {
      Eigen::VectorXd d;
      green.DiffusionDistance(frames[e], options.diffusion_steps, &d);
      FalloffFromDistance(d, frames[e], begin, end, falloff);
      falloff->sigma_used = green.sigma_used();
      falloff->eigenpairs_used = green.eigenpairs_used();
      falloff->sparse_used = green.sparse_used();
    }
  }
  return Status::Ok();
}

Status ComputeFalloff(const Skeleton& skeleton, const Motion& motion, int frame,
                      FalloffMethod method, const FalloffOptions& options, Falloff* falloff) {
  std::vector<Falloff> falloffs;
  Status status = ComputeFalloffs(skeleton, motion, {frame}, method, options, &falloffs);
  if (!status.ok()) return status;
  *falloff = std::move(falloffs[0]);
  return Status::Ok();
}

}  // namespace mocapsolve
