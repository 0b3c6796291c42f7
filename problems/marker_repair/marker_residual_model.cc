#include "problems/marker_repair/marker_residual_model.h"

#include <algorithm>
#include <cmath>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {
namespace {

// Median of v (reordered); 0 for an empty v.
double Median(std::vector<double>* v) {
  if (v->empty()) return 0.0;
  const size_t mid = v->size() / 2;
  std::nth_element(v->begin(), v->begin() + mid, v->end());
  return (*v)[mid];
}

int MainJoint(const MarkerSpec& marker) {
  int joint = marker.attachments.front().joint;
  double weight = -1.0;
  for (const MarkerAttachment& a : marker.attachments) {
    if (a.weight > weight) weight = a.weight, joint = a.joint;
  }
  return joint;
}

// clamp(median + k * 1.4826 MAD, min, max) of the deviations (reordered).
double RobustGate(std::vector<double>* deviations, const ResidualModelOptions& options, double* median,
                  double* scale) {
  std::vector<double> spread = *deviations;
  *median = Median(deviations);
  for (double& e : spread) e = std::abs(e - *median);
  *scale = 1.4826 * Median(&spread);
  double gate = std::max(*median + options.mads * *scale, options.min_distance);
  if (options.max_distance > 0.0) gate = std::min(gate, options.max_distance);
  return gate;
}

}  // namespace

MarkerResidualModel FitMarkerResidualModel(const Skeleton& skeleton, const MarkerSet& markers,
                                           const Motion& reference,
                                           const std::vector<std::vector<Eigen::Vector3d>>& reconstructed,
                                           const MarkerTrajectories& x, const ResidualModelOptions& options) {
  const int nf = x.num_frames(), nm = markers.num_markers();
  MarkerResidualModel model;
  model.predicted = reconstructed;
  model.typical_predicted = reconstructed;
  model.typical.assign(nm, Eigen::Vector3d::Zero());
  model.median_deviation.assign(nm, 0.0);
  model.scale.assign(nm, 0.0);
  model.gate.assign(nm, options.fixed_distance);
  model.typical_gate.assign(nm, options.fixed_distance);
  model.step_gate.assign(nm, 0.0);
  model.jumped.assign(nf, std::vector<char>(nm, 0));
  if (!options.robust) return model;
  std::vector<int> joint(nm);
  for (int m = 0; m < nm; ++m) joint[m] = MainJoint(markers.marker(m));
  // Reference rotations of each marker's joint, and local residuals d_fm (frame-major).
  std::vector<Eigen::Quaterniond> rotation(static_cast<size_t>(nf) * nm);
  std::vector<Eigen::Vector3d> local(static_cast<size_t>(nf) * nm, Eigen::Vector3d::Zero());
  FkData fk(skeleton);
  for (int f = 0; f < nf; ++f) {
    ForwardKinematics(skeleton, reference.frames[f], &fk);
    for (int m = 0; m < nm; ++m) {
      const size_t i = static_cast<size_t>(f) * nm + m;
      rotation[i] = fk.world_rotations[joint[m]];
      // X^ smoothed in time by the binomial [1 4 6 4 1] / 16 (exact on linear motion, zero
      // gain at the Nyquist rate): a per-frame reference that alternates between two
      // solutions (a solve that stopped early) makes no steps of the marker.
      Eigen::Vector3d rebuilt = reconstructed[f][m];
      if (f >= 2 && f + 2 < nf) {
        rebuilt = (reconstructed[f - 2][m] + 4.0 * reconstructed[f - 1][m] + 6.0 * reconstructed[f][m] +
                   4.0 * reconstructed[f + 1][m] + reconstructed[f + 2][m]) / 16.0;
      }
      if (x.valid(f, m)) local[i] = rotation[i].conjugate() * (x.position(f, m) - rebuilt);
    }
  }
  const int half = std::max(0, options.window / 2);
  std::vector<double> values, deviations;
  std::vector<Eigen::Vector3d> smooth(nf);
  for (int m = 0; m < nm; ++m) {
    auto d = [&](int f) -> const Eigen::Vector3d& { return local[static_cast<size_t>(f) * nm + m]; };
    // Take-wide typical residual and gate.
    for (int k = 0; k < 3; ++k) {
      values.clear();
      for (int f = 0; f < nf; ++f) {
        if (x.valid(f, m)) values.push_back(d(f)[k]);
      }
      model.typical[m][k] = Median(&values);
    }
    deviations.clear();
    for (int f = 0; f < nf; ++f) {
      if (x.valid(f, m)) deviations.push_back((d(f) - model.typical[m]).norm());
    }
    double median = 0.0, scale = 0.0;
    model.typical_gate[m] = RobustGate(&deviations, options, &median, &scale);
    // Soft-tissue residual: running median (the typical one where the window is empty),
    // at every `stride`-th frame and linear between.
    const int stride = 4;
    std::vector<int> knots;
    for (int f = 0; f < nf; f += stride) knots.push_back(f);
    if (knots.back() != nf - 1) knots.push_back(nf - 1);
    std::vector<Eigen::Vector3d> knot_values(knots.size());
    for (size_t i = 0; i < knots.size(); ++i) {
      const int f = knots[i], a = std::max(0, f - half), b = std::min(nf - 1, f + half);
      for (int k = 0; k < 3; ++k) {
        values.clear();
        for (int g = a; g <= b; ++g) {
          if (x.valid(g, m)) values.push_back(d(g)[k]);
        }
        knot_values[i][k] = values.empty() ? model.typical[m][k] : Median(&values);
      }
    }
    for (size_t i = 0; i + 1 < knots.size(); ++i) {
      for (int f = knots[i]; f <= knots[i + 1]; ++f) {
        const double t = double(f - knots[i]) / (knots[i + 1] - knots[i]);
        smooth[f] = (1.0 - t) * knot_values[i] + t * knot_values[i + 1];
      }
    }
    if (knots.size() == 1) smooth[0] = knot_values[0];
    // Steps: jumps of the residual between consecutive valid samples.
    deviations.clear();
    int previous = -1;
    for (int f = 0; f < nf; ++f) {
      if (!x.valid(f, m)) continue;
      if (previous >= 0 && previous == f - 1) deviations.push_back((d(f) - d(previous)).norm());
      previous = f;
    }
    ResidualModelOptions step_options = options;
    step_options.max_distance = 0.0;
    model.step_gate[m] = RobustGate(&deviations, step_options, &median, &scale);
    // A step into a displacement and the step back out (about opposite) bound an outlying
    // interval; an unmatched step condemns its own sample.
    std::vector<std::pair<int, Eigen::Vector3d>> steps;
    previous = -1;
    for (int f = 0; f < nf; ++f) {
      if (!x.valid(f, m)) continue;
      if (previous >= 0 && previous == f - 1 && (d(f) - d(previous)).norm() > model.step_gate[m]) {
        steps.push_back({f, d(f) - d(previous)});
      }
      previous = f;
    }
    for (size_t i = 0; i < steps.size(); ++i) {
      size_t match = i;
      for (size_t j = i + 1; j < steps.size() && steps[j].first - steps[i].first <= options.max_jump_frames; ++j) {
        // The way back out: opposite within the gate or half the step, or back to the
        // residual before the step within as much (while the marker is displaced the
        // residual drifts with the pose, and the robust reference slowly leans toward it,
        // so the step out can be much smaller than the step in).
        const int a = steps[i].first, b = steps[j].first;
        const Eigen::Vector3d before = d(a) - steps[i].second;
        const double tolerance = std::max(model.step_gate[m], 0.5 * steps[i].second.norm());
        if ((steps[i].second + steps[j].second).norm() > tolerance && (d(b) - before).norm() > tolerance) continue;
        // ...and displaced in between: the mean residual inside, against the last one
        // before, at least half the step along it (two unrelated steps far apart are no jump).
        Eigen::Vector3d inside = Eigen::Vector3d::Zero();
        int count = 0;
        for (int f = a; f < b; ++f) {
          if (x.valid(f, m)) inside += d(f), ++count;
        }
        const double along = (inside / std::max(count, 1) - before).dot(steps[i].second.normalized());
        if (count > 0 && along >= 0.5 * steps[i].second.norm()) { match = j; break; }
      }
      const int last = match > i ? steps[match].first - 1 : steps[i].first;
      // Only samples displaced past the floor from the soft-tissue residual: noise of a few
      // mm steps by a cm from frame to frame, and its refill would be worse than it.
      for (int f = steps[i].first; f <= last; ++f) {
        model.jumped[f][m] = x.valid(f, m) && (d(f) - smooth[f]).norm() > options.min_distance;
      }
      if (match > i) i = match;
    }
    deviations.clear();
    for (int f = 0; f < nf; ++f) {
      if (x.valid(f, m)) deviations.push_back((d(f) - smooth[f]).norm());
    }
    model.gate[m] = std::max(RobustGate(&deviations, options, &model.median_deviation[m], &model.scale[m]),
                             options.max_distance);
    for (int f = 0; f < nf; ++f) {
      const Eigen::Quaterniond& r = rotation[static_cast<size_t>(f) * nm + m];
      model.typical_predicted[f][m] += r * model.typical[m];
      model.predicted[f][m] += r * smooth[f];
    }
  }
  return model;
}

}  // namespace mocapsolve
