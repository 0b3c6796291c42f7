#include "signal/joint_gap_template.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glog/logging.h>

#include "kinematics/rotation.h"
#include "signal/joint_gap_carry.h"

namespace mocapsolve {
namespace {

double SquaredAngle(const Eigen::Quaterniond& p, const Eigen::Quaterniond& q) {
  const double angle = p.angularDistance(q);
  return angle * angle;
}

// Whether shift tau qualifies: the run's frames and the two around it, shifted by tau, lie
// in the take and have the joint observed (not carried).
bool SourceQualifies(int frames, const std::vector<std::vector<char>>& carried, const CarriedJointRun& run, int tau) {
  const int a = run.first - 1, b = run.last + 1;
  if (a + tau < 0 || b + tau >= frames) return false;
  for (int f = a; f <= b; ++f) {
    if (carried[run.joint][f + tau]) return false;
  }
  return true;
}

// Mean squared angle of the window at a qualifying shift tau (the bounds leave it a chance).
// +inf as soon as the sum so far shows the mean cannot be below `best` (the sum only
// grows, and at most max_counted pairs count): such a shift would not be chosen anyway,
// and most shifts are far off, so most windows stop after a few frames.
double MatchCost(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                 const CarriedJointRun& run, int lo, int hi, int tau, double best, double max_counted) {
  const int frames = motion.num_frames(), j = run.joint;
  const int a = run.first - 1, b = run.last + 1;
  double sum = 0.0;
  int counted = 0, possible = 0;
  for (int f = lo; f <= hi; ++f) {
    const int g = f + tau;
    if (g < 0 || g >= frames) {
      possible += skeleton.num_joints();
      continue;
    }
    for (int k = 1; k < skeleton.num_joints(); ++k) {
      if (skeleton.num_rotation_dofs(k) == 0) continue;
      const bool in_run = k == j && f > a && f < b;
      if (in_run) continue;
      ++possible;
      if (carried[k][f] || carried[k][g]) continue;
      sum += SquaredAngle(motion.frames[f].rotations[k], motion.frames[g].rotations[k]);
      ++counted;
    }
    if (sum > best * max_counted * (1.0 + 1e-9)) return std::numeric_limits<double>::infinity();
  }
  if (counted == 0 || 2 * counted < possible) return std::numeric_limits<double>::infinity();
  return sum / counted;
}

// Bounds of SquaredAngle without its atan2, from the two rotations made unit (u, v): with
// c = |u . v| the cosine and s = sqrt(1 - c^2) the sine of half the angle,
//   4 s^2 <= angle^2 <= 4 s^2 / c^2
// (sin x <= x <= tan x on [0, pi/2]); each moved by far more than its rounding (and the
// unit rotations' own) so it stays on its side of SquaredAngle as computed.
struct AngleBounds {
  double lower, upper;
};
AngleBounds SquaredAngleBounds(const double* u, const double* v) {
  const double c = u[0] * v[0] + u[1] * v[1] + u[2] * v[2] + u[3] * v[3];
  const double c2 = c * c, s2 = std::max(0.0, 1.0 - c2);
  return {std::max(0.0, 4.0 * s2 * (1.0 - 1e-9) - 1e-10), 4.0 * s2 / c2 * (1.0 + 1e-9) + 1e-10};
}

// A shift's window by the bounds: the sums of both over the pairs MatchCost counts, and its
// counts of pairs counted and possible (as MatchCost's). False when the shift does not qualify
// (SourceQualifies) or the lower sum passes `cut` (then the cost passes the best the cut was
// made from). Cheap (no atan2, the table's rows read in order).
struct WindowBounds {
  double lower = 0.0, upper = 0.0;
  int counted = 0, possible = 0;
};
bool BoundWindow(const Skeleton& skeleton, const JointTemplateTable& table, const std::vector<std::vector<char>>& carried,
                 int frames, const CarriedJointRun& run, int lo, int hi, int tau, double cut, WindowBounds* out) {
  const int j = run.joint;
  const int a = run.first - 1, b = run.last + 1;
  if (!SourceQualifies(frames, carried, run, tau)) return false;
  const std::vector<int>& joints = table.joints();
  const int n = static_cast<int>(joints.size());
  WindowBounds w;
  for (int f = lo; f <= hi; ++f) {
    const int g = f + tau;
    if (g < 0 || g >= frames) {
      w.possible += skeleton.num_joints();
      continue;
    }
    const double *uf = table.unit(f), *ug = table.unit(g);
    const char *cf = table.carried(f), *cg = table.carried(g);
    const bool in_run = f > a && f < b;
    for (int i = 0; i < n; ++i) {
      if (in_run && joints[i] == j) continue;
      ++w.possible;
      if (cf[i] || cg[i]) continue;
      ++w.counted;
      const AngleBounds bounds = SquaredAngleBounds(uf + 4 * i, ug + 4 * i);
      w.lower += bounds.lower;
      w.upper += bounds.upper;
    }
    if (w.lower > cut) return false;
  }
  *out = w;
  return true;
}

}  // namespace

JointTemplateTable::JointTemplateTable(const Skeleton& skeleton, const Motion& motion,
                                       const std::vector<std::vector<char>>& carried, int first, int last)
    : first_(first), frames_(std::max(0, last - first + 1)) {
  for (int k = 1; k < skeleton.num_joints(); ++k) {
    if (skeleton.num_rotation_dofs(k) > 0) joints_.push_back(k);
  }
  const size_t n = joints_.size(), frames = frames_;
  unit_.resize(4 * n * frames);
  carried_.resize(n * frames);
  for (size_t f = 0; f < frames; ++f) {
    const Pose& pose = motion.frames[first + f];
    for (size_t i = 0; i < n; ++i) {
      const int k = joints_[i];
      const Eigen::Vector4d& q = pose.rotations[k].coeffs();
      Eigen::Map<Eigen::Vector4d> unit(&unit_[4 * (n * f + i)]);
      unit = q / q.norm();
      carried_[n * f + i] = carried[k][first + f];
    }
  }
}

int FindTemplateShift(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                      const CarriedJointRun& run, const JointTemplateOptions& options) {
  const int frames = motion.num_frames();
  const int a = run.first - 1, b = run.last + 1;
  if (a < 0 || b >= frames) return 0;
  // The frames the shifts reach.
  int first = 0, last = frames - 1;
  if (options.max_shift_frames > 0) {
    first = std::max(0, a - options.margin - options.max_shift_frames);
    last = std::min(frames - 1, b + options.margin + options.max_shift_frames);
  }
  const JointTemplateTable table(skeleton, motion, carried, first, last);
  return FindTemplateShift(skeleton, motion, carried, table, run, options);
}

int FindTemplateShift(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                      const JointTemplateTable& table, const CarriedJointRun& run, const JointTemplateOptions& options) {
  const int frames = motion.num_frames();
  const int a = run.first - 1, b = run.last + 1;
  if (a < 0 || b >= frames) return 0;
  const int lo = std::max(0, a - options.margin), hi = std::min(frames - 1, b + options.margin);
  double best = options.max_rms_angle * options.max_rms_angle;
  int best_tau = 0;
  int min_tau = -a, max_tau = frames - 1 - b;
  if (options.max_shift_frames > 0) {
    min_tau = std::max(min_tau, -options.max_shift_frames);
    max_tau = std::min(max_tau, options.max_shift_frames);
  }
  CHECK(table.first() <= std::max(0, lo + min_tau) && table.last() >= std::min(frames - 1, hi + max_tau))
      << "the template table does not hold the frames the shifts reach";
  // Joints but the root with rotation dofs: at most this many pairs per frame count.
  const int rotating = static_cast<int>(table.joints().size());
  const double max_counted = static_cast<double>(rotating) * (hi - lo + 1);
  // The shifts whose bounds leave them a chance, by a scan that keeps the least upper bound of
  // a qualifying shift's cost met so far (the exact costs would fall one shift at a time along
  // the scan, each computed in full); then their exact costs, in the scan's order, from the
  // same start, skipping those whose lower bound passes the least upper bound: their costs
  // pass the least cost, so the shift chosen, ties to the first, is the scan's with every cost.
  struct Candidate {
    int tau;
    double lower;  // Lower bound of the cost.
  };
  std::vector<Candidate> candidates;
  double least_upper = best;
  for (int tau = min_tau; tau <= max_tau; ++tau) {
    if (tau == 0) continue;
    WindowBounds w;
    if (!BoundWindow(skeleton, table, carried, frames, run, lo, hi, tau, least_upper * max_counted * (1.0 + 1e-9), &w)) {
      continue;
    }
    if (w.counted == 0 || 2 * w.counted < w.possible) continue;  // MatchCost's +inf.
    const double lower = w.lower / w.counted;
    if (lower > least_upper * (1.0 + 1e-9)) continue;
    candidates.push_back({tau, lower});
    least_upper = std::min(least_upper, w.upper / w.counted * (1.0 + 1e-9));
  }
  for (const Candidate& c : candidates) {
    if (c.lower > least_upper * (1.0 + 1e-9)) continue;
    const double cost = MatchCost(skeleton, motion, carried, run, lo, hi, c.tau, best, max_counted);
    if (cost < best) {
      best = cost;
      best_tau = c.tau;
    }
  }
  return best_tau;
}

void CarryFromTemplate(const CarriedJointRun& run, int tau, Motion* motion) {
  const int j = run.joint, a = run.first - 1, b = run.last + 1;
  std::vector<Pose>& poses = motion->frames;
  const Eigen::Vector3d da = LogMap(poses[a + tau].rotations[j].conjugate() * poses[a].rotations[j]);
  const Eigen::Vector3d db = LogMap(poses[b + tau].rotations[j].conjugate() * poses[b].rotations[j]);
  const double n = b - a;
  for (int f = a + 1; f < b; ++f) {
    const double t = (f - a) / n, h = t * t * (3.0 - 2.0 * t);
    poses[f].rotations[j] = (poses[f + tau].rotations[j] * ExpMap((1.0 - h) * da + h * db)).normalized();
  }
}

}  // namespace mocapsolve
