#include "problems/marker_repair/marker_residual_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinematics/forward_kinematics.h"
#include "kinematics/rotation.h"
#include "signal/window_medians.h"

namespace mocapsolve {
namespace {

// A step of the marker seen from its joint's parent counts when the residual steps with
// it by at least this share of its length (the reference absorbs the rest).
constexpr double kConfirmedShare = 0.2;
// A paired jump whose steps in and out are both at least kSharpSteps times the marker's
// own step statistic (median + k MAD of its steps, before the floor) and that lasts less
// than half the soft-tissue window also condemns the samples displaced from the level
// before it by at least half the step in (the reference leans toward a displaced marker,
// which takes it under the floor from the soft-tissue residual).
constexpr double kSharpSteps = 5.0;
// A calm plateau, also under the floor: a step in and a step out of at least
// kPlateauSteps times the marker's own step statistic and kPlateauFloor times the floor,
// the step just before the one in, those inside and the one just after the one out all
// under kPlateauCalm times the step in, at least kPlateauShortest samples and less than
// half the soft-tissue window long: a displaced marker held still. Noise steps at every
// frame (no calm neighbours), soft tissue does not step. It counts only where the
// captured marker itself jumps at both ends: the second difference of its samples at
// least kPlateauRaw times the step (when the reference turns a joint toward a displaced
// marker, the joint's other markers get residual plateaus while their samples move
// smoothly). A single sample under the floor is not told from noise.
constexpr double kPlateauSteps = 3.0;
constexpr double kPlateauFloor = 0.5;
constexpr double kPlateauCalm = 0.3;
constexpr int kPlateauShortest = 2;
constexpr double kPlateauRaw = 0.5;
// A windowed calm plateau, for steps that single-frame steps cannot tell from white noise
// (1 mm per axis makes a marker's own step statistic ~7 mm, so a 1-1.5 cm jump is under
// kPlateauSteps of it): the step between the means of kWindow samples after and before a
// frame, D_f = mean(d_f..d_(f+k-1)) - mean(d_(f-k)..d_(f-1)), whose noise falls as
// 1/sqrt(k). A step in at a local peak of |D| of at least kWindowSteps times its own
// statistic (median + k MAD of |D| over the take) and kPlateauFloor times the floor, and
// one out at least kWindow samples later (a plateau no shorter than the windows, so they
// see its whole height) and less than half the soft-tissue window, back as for the
// plateaus; D calm (under kPlateauCalm of the step in) a window before the step in,
// between the steps and a window after the step out. Each end is put on the frame of the
// largest single step along D within one frame of the peak, where the raw-sample check of
// the plateaus then applies.
constexpr int kWindow = 4;
constexpr double kWindowSteps = 2.0;
// Knot spacing (frames) of the running medians: the soft-tissue residual's, and the
// steady frame's (computed for more signals, and smoother).
constexpr int kSoftTissueStride = 4;
constexpr int kSteadyStride = 16;

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


// Component-wise running median of value(f) over the valid frames within `half` of f,
// taken at every `stride`-th frame and linear between (`fallback` where a window is empty).
template <typename Valid, typename Value>
std::vector<Eigen::Vector3d> RunningMedian(int nf, int half, int stride, const Valid& valid, const Value& value,
                                           const Eigen::Vector3d& fallback) {
  std::vector<Eigen::Vector3d> samples(nf);
  std::vector<char> ok(nf);
  for (int f = 0; f < nf; ++f) {
    ok[f] = valid(f);
    if (ok[f]) samples[f] = value(f);
  }
  std::vector<int> knots;
  for (int f = 0; f < nf; f += stride) knots.push_back(f);
  if (knots.back() != nf - 1) knots.push_back(nf - 1);
  std::vector<Eigen::Vector3d> knot_values(knots.size());
  std::vector<double> component(nf, 0.0);
  for (int k = 0; k < 3; ++k) {
    for (int f = 0; f < nf; ++f) component[f] = ok[f] ? samples[f][k] : 0.0;
    const std::vector<double> medians = WindowMedians(component, ok, knots, half, fallback[k]);
    for (size_t i = 0; i < knots.size(); ++i) knot_values[i][k] = medians[i];
  }
  std::vector<Eigen::Vector3d> smooth(nf);
  for (size_t i = 0; i + 1 < knots.size(); ++i) {
    for (int f = knots[i]; f <= knots[i + 1]; ++f) {
      const double t = double(f - knots[i]) / (knots[i + 1] - knots[i]);
      smooth[f] = (1.0 - t) * knot_values[i] + t * knot_values[i + 1];
    }
  }
  if (knots.size() == 1) smooth[0] = knot_values[0];
  return smooth;
}

// Calm plateaus (see kPlateauSteps): a step v_a of at least `least`, the step before it
// calm, and within `longest` frames a step v_b of at least `least` back (|v_a + v_b|, or
// the residual after it against the one before v_a, within |v_a| / 2), every step in
// between and the one after v_b calm: samples a..b-1 are candidates, appended to
// `plateaus` (the caller judges them against the captured samples, which d may not be).
// Consecutive valid samples only; a gap ends the search.
struct Plateau {
  int marker, first, last;                   // Samples first..last displaced.
  double size;                               // |v_a|.
  std::vector<std::vector<char>>* target;    // jumped or absorbed.
};

template <typename Valid, typename Value, typename Confirm>
void FindPlateaus(int nf, int m, const Valid& valid, const Value& d, const Confirm& confirm, double least,
                  int longest, std::vector<std::vector<char>>* target, std::vector<Plateau>* plateaus) {
  auto step = [&](int f) -> Eigen::Vector3d {  // Zero where f or f - 1 is missing or out.
    if (f < 1 || f >= nf || !valid(f) || !valid(f - 1)) return Eigen::Vector3d::Zero();
    return d(f) - d(f - 1);
  };
  for (int a = 1; a < nf; ++a) {
    const Eigen::Vector3d in = step(a);
    const double size = in.norm();
    if (size < least || !valid(a) || !valid(a - 1)) continue;
    const double calm = kPlateauCalm * size;
    if (step(a - 1).norm() > calm || !confirm(a, in)) continue;
    const Eigen::Vector3d before = d(a - 1);
    for (int b = a + 1; b < nf && b - a <= longest && valid(b) && valid(b - 1); ++b) {
      const Eigen::Vector3d out = step(b);
      if (out.norm() < least) {
        if (out.norm() > calm) break;  // Neither calm nor a step back: no plateau.
        continue;
      }
      // The way back out: opposite, or back to the level before, within half the step.
      const bool back = (in + out).norm() <= 0.5 * size || (d(b) - before).norm() <= 0.5 * size;
      if (b - a >= kPlateauShortest && back && step(b + 1).norm() <= calm && confirm(b, out)) {
        plateaus->push_back({m, a, b - 1, size, target});
        a = b;
      }
      break;
    }
  }
}

template <typename Valid, typename Value, typename Confirm>
void FindWindowedPlateaus(int nf, int m, const Valid& valid, const Value& d, const Confirm& confirm,
                          const ResidualModelOptions& options, std::vector<std::vector<char>>* target,
                          std::vector<Plateau>* plateaus) {
  const int k = kWindow;
  if (nf < 4 * k) return;
  std::vector<Eigen::Vector3d> sum(nf + 1, Eigen::Vector3d::Zero());  // Prefix sums over valid samples.
  std::vector<int> count(nf + 1, 0);
  for (int f = 0; f < nf; ++f) {
    const bool ok = valid(f);
    sum[f + 1] = sum[f] + (ok ? Eigen::Vector3d(d(f)) : Eigen::Vector3d::Zero());
    count[f + 1] = count[f] + ok;
  }
  // D_f where both windows are fully observed (NaN elsewhere).
  std::vector<Eigen::Vector3d> step(nf, Eigen::Vector3d::Constant(std::nan("")));
  std::vector<double> sizes;
  for (int f = k; f + k <= nf; ++f) {
    if (count[f + k] - count[f - k] != 2 * k) continue;
    step[f] = ((sum[f + k] - sum[f]) - (sum[f] - sum[f - k])) / k;
    sizes.push_back(step[f].norm());
  }
  if (sizes.size() < 4 * static_cast<size_t>(k)) return;
  ResidualModelOptions window_options = options;
  window_options.min_distance = window_options.max_distance = 0.0;
  double median = 0.0, scale = 0.0;
  RobustGate(&sizes, window_options, &median, &scale);
  const double least = std::max(kWindowSteps * (median + options.mads * scale), kPlateauFloor * options.min_distance);
  auto size = [&](int f) { return f >= 0 && f < nf && step[f].allFinite() ? step[f].norm() : -1.0; };
  auto peak = [&](int f) { return size(f) >= least && size(f) >= size(f - 1) && size(f) >= size(f + 1); };
  auto calm = [&](int f, double limit) { return size(f) >= 0.0 && size(f) <= limit; };
  // The frame within one of f whose single step along D_f is largest.
  auto sharpest = [&](int f) {
    int best = f;
    double along = -std::numeric_limits<double>::infinity();
    for (int g = f - 1; g <= f + 1; ++g) {
      if (g < 1 || g >= nf || !valid(g) || !valid(g - 1)) continue;
      const double a = (d(g) - d(g - 1)).dot(step[f].normalized());
      if (a > along) along = a, best = g;
    }
    return best;
  };
  const int longest = options.window / 2;
  for (int a = k; a < nf; ++a) {
    if (!peak(a)) continue;
    const double height = size(a), limit = kPlateauCalm * height;
    if (!calm(a - k, limit)) continue;
    int b = a + k;
    while (b < nf && b - a < longest && !peak(b)) ++b;
    if (b >= nf || b - a >= longest) continue;
    bool quiet = calm(b + k, limit);
    for (int f = a + k; f <= b - k && quiet; ++f) quiet = calm(f, limit);
    const Eigen::Vector3d before = (sum[a] - sum[a - k]) / k, after = (sum[b + k] - sum[b]) / k;
    const bool back = (step[a] + step[b]).norm() <= 0.5 * height || (after - before).norm() <= 0.5 * height;
    if (!quiet || !back) continue;
    const int in = sharpest(a), out = sharpest(b);
    if (out - in < k || !confirm(in, d(in) - d(in - 1)) || !confirm(out, d(out) - d(out - 1))) continue;
    plateaus->push_back({m, in, out - 1, height, target});
    a = b;
  }
}

// The robust gate of the steps d(f) - d(f-1) between consecutive valid samples (at least
// min_distance, no cap), and the paired steps past it marked in jumped[f][m] where the
// sample is displaced past min_distance from smooth[f] (see the header).
template <typename Valid, typename Value, typename Confirm>
double MarkJumps(int nf, int m, const Valid& valid, const Value& d, const Confirm& confirm,
                 const std::vector<Eigen::Vector3d>& smooth, const ResidualModelOptions& options,
                 std::vector<std::vector<char>>* jumped, std::vector<Plateau>* plateaus) {
  std::vector<double> deviations;
  int previous = -1;
  for (int f = 0; f < nf; ++f) {
    if (!valid(f)) continue;
    if (previous >= 0 && previous == f - 1) deviations.push_back((d(f) - d(previous)).norm());
    previous = f;
  }
  ResidualModelOptions step_options = options;
  step_options.max_distance = 0.0;
  double median = 0.0, scale = 0.0;
  const double step_gate = RobustGate(&deviations, step_options, &median, &scale);
  // A step into a displacement and the step back out (about opposite) bound an outlying
  // interval; an unmatched step condemns its own sample.
  std::vector<std::pair<int, Eigen::Vector3d>> steps;
  previous = -1;
  for (int f = 0; f < nf; ++f) {
    if (!valid(f)) continue;
    if (previous >= 0 && previous == f - 1 && (d(f) - d(previous)).norm() > step_gate &&
        confirm(f, d(f) - d(previous))) {
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
      const double tolerance = std::max(step_gate, 0.5 * steps[i].second.norm());
      if ((steps[i].second + steps[j].second).norm() > tolerance && (d(b) - before).norm() > tolerance) continue;
      // ...and displaced in between: the mean residual inside, against the last one
      // before, at least half the step along it (two unrelated steps far apart are no jump).
      Eigen::Vector3d inside = Eigen::Vector3d::Zero();
      int count = 0;
      for (int f = a; f < b; ++f) {
        if (valid(f)) inside += d(f), ++count;
      }
      const double along = (inside / std::max(count, 1) - before).dot(steps[i].second.normalized());
      if (count > 0 && along >= 0.5 * steps[i].second.norm()) { match = j; break; }
    }
    const int last = match > i ? steps[match].first - 1 : steps[i].first;
    // Only samples displaced past the floor from the soft-tissue residual: noise of a few
    // mm steps by a cm from frame to frame, and its refill would be worse than it.
    // A sharp, short pair: also the samples displaced from the level before it.
    const Eigen::Vector3d before = d(steps[i].first) - steps[i].second;
    const Eigen::Vector3d along = steps[i].second.normalized();
    const bool sharp = match > i && 2 * (last - steps[i].first) < options.window &&
                       std::min(steps[i].second.norm(), steps[match].second.norm()) >=
                           kSharpSteps * (median + options.mads * scale);
    for (int f = steps[i].first; f <= last; ++f) {
      if (valid(f) && ((d(f) - smooth[f]).norm() > options.min_distance ||
                       (sharp && (d(f) - before).dot(along) >= 0.5 * steps[i].second.norm()))) {
        (*jumped)[f][m] = 1;
      }
    }
    if (match > i) i = match;
  }
  FindPlateaus(nf, m, valid, d, confirm, std::max(kPlateauSteps * (median + options.mads * scale),
                                                   kPlateauFloor * options.min_distance),
               options.window / 2, jumped, plateaus);
  FindWindowedPlateaus(nf, m, valid, d, confirm, options, jumped, plateaus);
  return step_gate;
}

// A plateau is a displacement of the marker only where the captured marker itself
// jumps: its second difference at the step in (and at the step out) at least
// kPlateauRaw times the step. When the reference turns a joint toward a displaced
// marker, the other markers of that joint (and of its children) get residual plateaus
// of their own while their samples move smoothly. Missing neighbours: no evidence, kept.
// Marks those plateaus' frames in their targets.
void MarkRawPlateaus(const MarkerTrajectories& x, const std::vector<Plateau>& plateaus) {
  const int nf = x.num_frames();
  // |(x_f - x_(f-1)) - (x_g - x_(g-1))|, or +inf where a sample is missing.
  auto jerk = [&](int m, int f, int g) -> double {
    const int lo = std::min(f, g) - 1, hi = std::max(f, g);
    if (lo < 0 || hi >= nf) return std::numeric_limits<double>::infinity();
    for (int k = lo; k <= hi; ++k) {
      if (!x.valid(k, m)) return std::numeric_limits<double>::infinity();
    }
    return ((x.position(f, m) - x.position(f - 1, m)) - (x.position(g, m) - x.position(g - 1, m))).norm();
  };
  for (const Plateau& plateau : plateaus) {
    const int m = plateau.marker, a = plateau.first, b = plateau.last + 1;
    const double least = kPlateauRaw * plateau.size;
    if (jerk(m, a, a - 1) < least || jerk(m, b, b + 1) < least) continue;
    for (int f = a; f <= plateau.last; ++f) (*plateau.target)[f][m] = 1;
  }
}

// The model with X^_fm read as reconstructed(f, m) (observations or trajectories).
template <typename Reconstructed>
MarkerResidualModel FitModel(const Skeleton& skeleton, const MarkerSet& markers, const Motion& reference,
                             const Reconstructed& reconstructed, const MarkerTrajectories& x,
                             const ResidualModelOptions& options) {
  const int nf = x.num_frames(), nm = markers.num_markers();
  MarkerResidualModel model;
  model.predicted.assign(nf, std::vector<Eigen::Vector3d>(nm));
  for (int f = 0; f < nf; ++f) {
    for (int m = 0; m < nm; ++m) model.predicted[f][m] = reconstructed(f, m);
  }
  model.typical_predicted = model.predicted;
  model.typical.assign(nm, Eigen::Vector3d::Zero());
  model.median_deviation.assign(nm, 0.0);
  model.scale.assign(nm, 0.0);
  model.gate.assign(nm, options.fixed_distance);
  model.typical_gate.assign(nm, options.fixed_distance);
  model.step_gate.assign(nm, 0.0);
  model.jumped.assign(nf, std::vector<char>(nm, 0));
  model.absorbed.assign(nf, std::vector<char>(nm, 0));
  if (!options.robust) return model;
  std::vector<int> joint(nm);
  for (int m = 0; m < nm; ++m) joint[m] = MainJoint(markers.marker(m));
  // The reference's world rotation and origin of each joint that carries a marker, per
  // frame (frame-major; held per joint, not per marker: a long take's largest array here).
  std::vector<int> carriers, slot(nm);
  for (int m = 0; m < nm; ++m) {
    const auto it = std::find(carriers.begin(), carriers.end(), joint[m]);
    slot[m] = static_cast<int>(it - carriers.begin());
    if (it == carriers.end()) carriers.push_back(joint[m]);
  }
  const size_t nc = carriers.size();
  std::vector<Eigen::Quaterniond> carrier_rotation(static_cast<size_t>(nf) * nc);
  std::vector<Eigen::Vector3d> carrier_origin(static_cast<size_t>(nf) * nc);
  FkData fk(skeleton);
  for (int f = 0; f < nf; ++f) {
    ForwardKinematics(skeleton, reference.frames[f], &fk);
    for (size_t c = 0; c < nc; ++c) {
      carrier_rotation[f * nc + c] = fk.world_rotations[carriers[c]];
      carrier_origin[f * nc + c] = fk.world_positions[carriers[c]];
    }
  }
  auto rotation = [&](int f, int m) -> const Eigen::Quaterniond& { return carrier_rotation[f * nc + slot[m]]; };
  // Marker m's local residuals d_fm and u_fm (see below), every frame (0 where x is missing).
  std::vector<Eigen::Vector3d> local(nf), unpinned(nf);
  auto residuals_of = [&](int m) {
    for (int f = 0; f < nf; ++f) {
      local[f] = unpinned[f] = Eigen::Vector3d::Zero();
      if (!x.valid(f, m)) continue;
      // X^ smoothed in time by the binomial [1 4 6 4 1] / 16 (exact on linear motion, zero
      // gain at the Nyquist rate): a per-frame reference that alternates between two
      // solutions (a solve that stopped early) makes no steps of the marker.
      Eigen::Vector3d rebuilt = reconstructed(f, m);
      if (f >= 2 && f + 2 < nf) {
        rebuilt = (reconstructed(f - 2, m) + 4.0 * reconstructed(f - 1, m) + 6.0 * reconstructed(f, m) +
                   4.0 * reconstructed(f + 1, m) + reconstructed(f + 2, m)) / 16.0;
      }
      local[f] = rotation(f, m).conjugate() * (x.position(f, m) - rebuilt);
      unpinned[f] = reference.frames[f].rotations[joint[m]] *
                    (rotation(f, m).conjugate() * (x.position(f, m) - carrier_origin[f * nc + slot[m]]));
    }
  };
  const int half = std::max(0, options.window / 2);
  // Each joint's own rotation, median-filtered (computed for the joints that need it): a
  // turn of 1-20 frames that follows a jumped marker is not in it.
  std::vector<std::vector<Eigen::Quaterniond>> steady(skeleton.num_joints());
  auto steady_rotations = [&](int j) -> const std::vector<Eigen::Quaterniond>& {
    std::vector<Eigen::Quaterniond>& q = steady[j];
    if (!q.empty()) return q;
    const auto log = RunningMedian(nf, half, kSteadyStride, [](int) { return true; },
                                   [&](int f) { return LogMap(reference.frames[f].rotations[j]); },
                                   Eigen::Vector3d::Zero());
    q.resize(nf);
    for (int f = 0; f < nf; ++f) q[f] = ExpMap(log[f]);
    return q;
  };
  std::vector<double> values, deviations;
  std::vector<Plateau> plateaus;
  std::vector<Eigen::Vector3d> smooth(nf);
  for (int m = 0; m < nm; ++m) {
    residuals_of(m);
    auto d = [&](int f) -> const Eigen::Vector3d& { return local[f]; };
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
    // Soft-tissue residual: running median (the typical one where the window is empty).
    auto valid = [&](int f) { return x.valid(f, m); };
    smooth = RunningMedian(nf, half, kSoftTissueStride, valid, d, model.typical[m]);
    model.step_gate[m] = MarkJumps(nf, m, valid, d, [](int, const Eigen::Vector3d&) { return true; }, smooth, options,
                                   &model.jumped, &plateaus);
    // Jumps the reference absorbed: steps of the marker seen from its joint's parent that
    // the residual confirms. A step of the steady-frame signal is about the step of u
    // turned by the steady rotation, so u finds the markers that have a candidate at all.
    const int j = joint[m];
    auto u = [&](int f) -> const Eigen::Vector3d& { return unpinned[f]; };
    auto confirmed = [&](int f, const Eigen::Vector3d& step_in_joint, double size) {
      return (d(f) - d(f - 1)).dot(step_in_joint.normalized()) >= kConfirmedShare * size;
    };
    bool candidate = false;
    for (int f = 1; f < nf && !candidate; ++f) {
      if (!x.valid(f, m) || !x.valid(f - 1, m)) continue;
      const Eigen::Vector3d step = u(f) - u(f - 1);
      candidate = step.norm() > 0.8 * options.min_distance &&
                  confirmed(f, reference.frames[f].rotations[j].conjugate() * step, step.norm());
    }
    if (candidate) {
      const std::vector<Eigen::Quaterniond>& q = steady_rotations(j);
      auto p = [&](int f) -> Eigen::Vector3d { return q[f].conjugate() * u(f); };
      const auto p_smooth = RunningMedian(nf, half, kSteadyStride, valid, p, Eigen::Vector3d::Zero());
      auto confirm = [&](int f, const Eigen::Vector3d& step) {
        return confirmed(f, reference.frames[f].rotations[j].conjugate() * (q[f] * step), step.norm());
      };
      MarkJumps(nf, m, valid, p, confirm, p_smooth, options, &model.absorbed, &plateaus);
    }
    deviations.clear();
    for (int f = 0; f < nf; ++f) {
      if (x.valid(f, m)) deviations.push_back((d(f) - smooth[f]).norm());
    }
    model.gate[m] = std::max(RobustGate(&deviations, options, &model.median_deviation[m], &model.scale[m]),
                             options.max_distance);
    for (int f = 0; f < nf; ++f) {
      const Eigen::Quaterniond& r = rotation(f, m);
      model.typical_predicted[f][m] += r * model.typical[m];
      model.predicted[f][m] += r * smooth[f];
    }
  }
  MarkRawPlateaus(x, plateaus);
  return model;
}

}  // namespace

MarkerResidualModel FitMarkerResidualModel(const Skeleton& skeleton, const MarkerSet& markers,
                                           const Motion& reference,
                                           const std::vector<std::vector<Eigen::Vector3d>>& reconstructed,
                                           const MarkerTrajectories& x, const ResidualModelOptions& options) {
  return FitModel(skeleton, markers, reference, [&](int f, int m) { return reconstructed[f][m]; }, x, options);
}

MarkerResidualModel FitMarkerResidualModel(const Skeleton& skeleton, const MarkerSet& markers,
                                           const Motion& reference, const MarkerTrajectories& reconstructed,
                                           const MarkerTrajectories& x, const ResidualModelOptions& options) {
  return FitModel(skeleton, markers, reference, [&](int f, int m) { return reconstructed.position(f, m); }, x,
                  options);
}

}  // namespace mocapsolve
