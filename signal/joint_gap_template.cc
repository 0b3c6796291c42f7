#include "signal/joint_gap_template.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

// Mean squared angle of the window at a qualifying shift tau (MayMatch checks it first).
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

// A lower bound of SquaredAngle without its atan2: with c = |p . q| / (|p| |q|) the cosine
// of half the angle, angle^2 >= 4 sin^2(angle / 2) = 4 (1 - c^2) (sin x <= x on [0, pi/2]);
// shrunk by far more than its rounding so it stays below SquaredAngle as computed.
double SquaredAngleLowerBound(const Eigen::Quaterniond& p, const Eigen::Quaterniond& q) {
  const double c = p.coeffs().dot(q.coeffs());
  const double sin2 = 1.0 - c * c / (p.coeffs().squaredNorm() * q.coeffs().squaredNorm());
  return 4.0 * sin2 * (1.0 - 1e-9) - 1e-10;
}

// False when the shift does not qualify (SourceQualifies) or MatchCost is sure to be +inf: the
// window's sum of lower bounds already passes the cut MatchCost stops at. Cheap (no atan2),
// so the exact cost is computed only for the few shifts this does not rule out; the result
// is MatchCost's either way.
bool MayMatch(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
              const CarriedJointRun& run, int lo, int hi, int tau, double best, double max_counted) {
  const int frames = motion.num_frames(), j = run.joint;
  const int a = run.first - 1, b = run.last + 1;
  if (!SourceQualifies(frames, carried, run, tau)) return false;
  const double cut = best * max_counted * (1.0 + 1e-9);
  double sum = 0.0;
  for (int f = std::max(lo, -tau); f <= std::min(hi, frames - 1 - tau); ++f) {
    const int g = f + tau;
    for (int k = 1; k < skeleton.num_joints(); ++k) {
      if (skeleton.num_rotation_dofs(k) == 0 || (k == j && f > a && f < b)) continue;
      if (carried[k][f] || carried[k][g]) continue;
      sum += std::max(0.0, SquaredAngleLowerBound(motion.frames[f].rotations[k], motion.frames[g].rotations[k]));
    }
    if (sum > cut) return false;
  }
  return true;
}

}  // namespace

int FindTemplateShift(const Skeleton& skeleton, const Motion& motion, const std::vector<std::vector<char>>& carried,
                      const CarriedJointRun& run, const JointTemplateOptions& options) {
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
  int rotating = 0;  // Joints but the root with rotation dofs: at most this many pairs per frame count.
  for (int k = 1; k < skeleton.num_joints(); ++k) rotating += skeleton.num_rotation_dofs(k) > 0 ? 1 : 0;
  const double max_counted = static_cast<double>(rotating) * (hi - lo + 1);
  for (int tau = min_tau; tau <= max_tau; ++tau) {
    if (tau == 0) continue;
    if (!MayMatch(skeleton, motion, carried, run, lo, hi, tau, best, max_counted)) continue;
    const double cost = MatchCost(skeleton, motion, carried, run, lo, hi, tau, best, max_counted);
    if (cost < best) {
      best = cost;
      best_tau = tau;
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
