#include "problems/marker_solve/marker_weights.h"

#include <algorithm>
#include <cmath>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "problems/marker_solve/sequence_solver.h"

namespace mocapsolve {

namespace {

// One round: solve with `markers` (their current weights) and measure the spreads.
Status LearnRound(const Skeleton& skeleton, const MarkerSet& markers,
                  const std::vector<std::vector<Eigen::Vector3d>>& observed, const MarkerSolveOptions& options,
                  const MarkerWeightOptions& weight_options, LearnedMarkerWeights* out) {
  const int num_markers = markers.num_markers();
  Motion motion;
  SequenceSolveReport report;
  Status status = SolveSequence(skeleton, markers, observed, options, RestPose(skeleton), &motion, &report);
  if (!status.ok()) return status;
  std::vector<double> sum(num_markers, 0.0);
  out->samples.assign(num_markers, 0);
  FkData fk(skeleton);
  for (size_t f = 0; f < observed.size(); ++f) {
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < num_markers; ++m) {
      if (!observed[f][m].allFinite()) continue;
      sum[m] += (markers.Position(m, fk) - observed[f][m]).squaredNorm();
      ++out->samples[m];
    }
  }
  out->sigma.assign(num_markers, 0.0);
  std::vector<double> measured;
  for (int m = 0; m < num_markers; ++m) {
    if (out->samples[m] < weight_options.min_samples) continue;
    out->sigma[m] = std::sqrt(sum[m] / out->samples[m]);
    measured.push_back(out->sigma[m]);
  }
  out->weight.assign(num_markers, 1.0);
  if (measured.empty()) return Status::Ok();
  std::sort(measured.begin(), measured.end());
  out->sigma_ref = measured[(measured.size() - 1) / 2];
  for (int m = 0; m < num_markers; ++m) {
    if (out->samples[m] < weight_options.min_samples || !(out->sigma[m] > out->sigma_ref)) continue;
    const double ratio = out->sigma_ref / out->sigma[m];
    out->weight[m] = std::max(weight_options.min_weight, ratio * ratio);
  }
  return Status::Ok();
}

}  // namespace

Status LearnMarkerWeights(const Skeleton& skeleton, const MarkerSet& markers,
                          const std::vector<std::vector<Eigen::Vector3d>>& observed,
                          const MarkerSolveOptions& options, const MarkerWeightOptions& weight_options,
                          LearnedMarkerWeights* learned) {
  if (!(weight_options.min_weight > 0.0 && weight_options.min_weight <= 1.0)) {
    return Status::Error("marker weights: min_weight must be in (0, 1]");
  }
  if (weight_options.rounds < 1) return Status::Error("marker weights: rounds must be >= 1");
  if (observed.empty()) return Status::Error("marker weights: no frames to learn from");
  LearnedMarkerWeights out;
  MarkerSet current = markers;
  for (int round = 0; round < weight_options.rounds; ++round) {
    Status status = LearnRound(skeleton, current, observed, options, weight_options, &out);
    if (status.ok() && round + 1 < weight_options.rounds) status = ApplyMarkerWeights(skeleton, markers, out.weight, &current);
    if (!status.ok()) return status;
  }
  *learned = std::move(out);
  return Status::Ok();
}

Status ApplyMarkerWeights(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<double>& weights,
                          MarkerSet* weighted) {
  if (static_cast<int>(weights.size()) != markers.num_markers()) {
    return Status::Error("marker weights: " + std::to_string(weights.size()) + " weights for " +
                         std::to_string(markers.num_markers()) + " markers");
  }
  std::vector<MarkerSpec> specs;
  for (int m = 0; m < markers.num_markers(); ++m) {
    specs.push_back(markers.marker(m));
    specs.back().solve_weight = weights[m];
  }
  return MarkerSet::Create(skeleton, std::move(specs), weighted);
}

}  // namespace mocapsolve
