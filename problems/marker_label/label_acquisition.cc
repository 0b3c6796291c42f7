#include "problems/marker_label/label_acquisition.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/marker_observations.h"

namespace mocapsolve {
namespace {

constexpr double kFirstGate = 16.0;  // The first matching round's gate, in gates.
constexpr int kLimbRounds = 6;          // RestartLimbs' match-and-solve rounds per limb,
constexpr double kLimbFirstGate = 4.0;  // the first at this many gates.

struct Placement {
  Eigen::Isometry3d world_from_joint = Eigen::Isometry3d::Identity();
  int joint = -1;
  int inliers = 0;
  double error = 0.0;
};

// The cluster's three markers spanning the largest triangle.
std::array<int, 3> LargestTriangle(const RigidCluster& cluster) {
  std::array<int, 3> best = {0, 1, 2};
  double best_area = -1.0;
  const int n = static_cast<int>(cluster.markers.size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      for (int c = b + 1; c < n; ++c) {
        const double area =
            (cluster.offsets[b] - cluster.offsets[a]).cross(cluster.offsets[c] - cluster.offsets[a]).norm();
        if (area > best_area) best_area = area, best = {a, b, c};
      }
    }
  }
  return best;
}

// Scores a world_from_joint by the cluster markers that land near a point.
void ScorePlacement(const RigidCluster& cluster, const std::vector<Eigen::Vector3d>& points, double tolerance,
                    Placement* placement) {
  placement->inliers = 0;
  placement->error = 0.0;
  for (const Eigen::Vector3d& z : cluster.offsets) {
    const Eigen::Vector3d p = placement->world_from_joint * z;
    double best = tolerance;
    for (const Eigen::Vector3d& u : points) best = std::min(best, (u - p).norm());
    placement->inliers += best < tolerance;
    placement->error += best;
  }
}

// The best placements of one cluster's joint among the cloud's matching triangles.
std::vector<Placement> ClusterPlacements(const RigidCluster& cluster, const std::vector<Eigen::Vector3d>& points,
                                         const AcquisitionOptions& options) {
  const std::array<int, 3> t = LargestTriangle(cluster);
  const Eigen::Vector3d& za = cluster.offsets[t[0]];
  const Eigen::Vector3d& zb = cluster.offsets[t[1]];
  const Eigen::Vector3d& zc = cluster.offsets[t[2]];
  const double dab = (za - zb).norm(), dbc = (zb - zc).norm(), dac = (za - zc).norm();
  const double tol = options.cluster_tolerance;
  Eigen::Matrix3d source;
  source << za, zb, zc;
  std::vector<Placement> found;
  const int n = static_cast<int>(points.size());
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (j == i || std::abs((points[i] - points[j]).norm() - dab) > tol) continue;
      for (int k = 0; k < n; ++k) {
        if (k == i || k == j || std::abs((points[j] - points[k]).norm() - dbc) > tol ||
            std::abs((points[i] - points[k]).norm() - dac) > tol) {
          continue;
        }
        Eigen::Matrix3d target;
        target << points[i], points[j], points[k];
        Placement placement;
        placement.joint = cluster.joint;
        placement.world_from_joint.matrix() = Eigen::umeyama(source, target, false);
        ScorePlacement(cluster, points, tol, &placement);
        found.push_back(placement);
      }
    }
  }
  std::sort(found.begin(), found.end(), [](const Placement& a, const Placement& b) {
    return a.inliers != b.inliers ? a.inliers > b.inliers : a.error < b.error;
  });
  if (static_cast<int>(found.size()) > options.hypotheses_per_cluster) found.resize(options.hypotheses_per_cluster);
  return found;
}

// `start` moved rigidly so that joint `joint` has the world transform `world_from_joint`.
Pose PlaceBody(const Skeleton& skeleton, const Pose& start, int joint, const Eigen::Isometry3d& world_from_joint) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, start, &fk);
  const Eigen::Quaterniond rotation(world_from_joint.rotation());
  const Eigen::Quaterniond move = (rotation * fk.world_rotations[joint].inverse()).normalized();
  const Eigen::Vector3d shift = world_from_joint.translation() - move * fk.world_positions[joint];
  Pose pose = start;
  const Eigen::Quaterniond rest =
      skeleton.has_rest_rotation(0) ? skeleton.rest_rotation(0) : Eigen::Quaterniond::Identity();
  pose.rotations[0] = (rest.inverse() * move * rest * start.rotations[0]).normalized();
  pose.translations[0] = move * start.translations[0] + shift;
  return pose;
}

// Match-and-solve rounds from `pose`; returns the placement's score (lower is better).
double RefinePlacement(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                       const AcquisitionOptions& options, MarkerFrameSolver* solver, Pose* pose,
                       GatedAssignment* matches) {
  const int num_markers = markers.num_markers();
  const Eigen::Vector3d nan = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (int round = 0; round <= options.iterations; ++round) {
    // The gate shrinks geometrically from kFirstGate gates to one over the rounds.
    const double left = round >= options.iterations ? 0.0 : (options.iterations - 1.0 - round) /
                                                                 std::max(1, options.iterations - 1);
    const double factor = std::pow(kFirstGate, left);
    const std::vector<double> gate(num_markers, options.gate * factor);
    AssignGated(ModelMarkerPositions(skeleton, markers, *pose), gate, points, matches);
    if (round == options.iterations) break;
    std::vector<Eigen::Vector3d> observed(num_markers, nan);
    int count = 0;
    for (int m = 0; m < num_markers; ++m) {
      const int k = matches->point_of_marker[m];
      if (k >= 0) observed[m] = points[k], ++count;
    }
    if (count < 3) break;
    FrameSolveReport report;
    Pose solved = *pose;
    if (solver->Solve(observed, &solved, &report).ok() && report.usable) *pose = solved;
  }
  double score = 0.0;
  for (int m = 0; m < num_markers; ++m) {
    const double e = matches->point_of_marker[m] >= 0 ? matches->distance[m] / options.gate : 1.0;
    score += std::min(e * e, 1.0);
  }
  return score;
}


// The limbs: the subtree of every joint but the root that carries two or more markers
// (a leg, a shin and foot, an arm, a hand, the head), as a mask over joints (parents
// come before their children in a Skeleton).
std::vector<std::vector<char>> Limbs(const Skeleton& skeleton, const MarkerSet& markers) {
  const int n = skeleton.num_joints();
  std::vector<int> carried(n, 0);  // Markers attached in the subtree of each joint.
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (const auto& attachment : markers.marker(m).attachments) ++carried[attachment.joint];
  }
  for (int j = n - 1; j > 0; --j) carried[skeleton.parent(j)] += carried[j];
  std::vector<std::vector<char>> limbs;
  for (int r = 1; r < n; ++r) {
    if (carried[r] < 2) continue;
    std::vector<char> in(n, 0);
    in[r] = 1;
    for (int j = r + 1; j < n; ++j) in[j] = skeleton.parent(j) >= 0 && in[skeleton.parent(j)];
    limbs.push_back(std::move(in));
  }
  return limbs;
}

// Local search over the matches: exchanges of the points of two, or cycles of three,
// matched markers whose points lie within 3 gates of each other, each kept when the
// solved cost drops by more than 10 % (the refinement's fixed point can hold the markers
// of a foot or a wrist in a rotated order the rounds cannot leave), then the matches made
// again from the polished pose.
}  // namespace

bool RestartLimbs(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                  const Pose& start, double gate, double keep_ratio, MarkerFrameSolver* solver, Pose* pose,
                  GatedAssignment* matches) {
  const int num_markers = markers.num_markers();
  const Eigen::Vector3d nan = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  bool changed = false;
  double best = SolvedCost(skeleton, markers, points, matches->point_of_marker, gate, solver, pose);
  for (const std::vector<char>& limb : Limbs(skeleton, markers)) {
    std::vector<char> on_limb(num_markers, 0);
    for (int m = 0; m < num_markers; ++m) {
      for (const auto& attachment : markers.marker(m).attachments) on_limb[m] |= limb[attachment.joint];
    }
    Pose trial_pose = *pose;
    for (int j = 0; j < skeleton.num_joints(); ++j) {
      if (limb[j]) trial_pose.rotations[j] = start.rotations[j];
    }
    std::vector<int> trial = matches->point_of_marker;
    std::vector<char> used(points.size(), 0);
    for (int m = 0; m < num_markers; ++m) {
      if (on_limb[m]) trial[m] = -1;
      else if (trial[m] >= 0) used[trial[m]] = 1;
    }
    std::vector<Eigen::Vector3d> free_points;
    std::vector<int> free_index;
    for (size_t k = 0; k < points.size(); ++k) {
      if (!used[k]) free_points.push_back(points[k]), free_index.push_back(static_cast<int>(k));
    }
    for (int round = 0; round < kLimbRounds; ++round) {
      const double factor = std::pow(kLimbFirstGate, (kLimbRounds - 1.0 - round) / (kLimbRounds - 1.0));
      std::vector<Eigen::Vector3d> predicted = ModelMarkerPositions(skeleton, markers, trial_pose);
      for (int m = 0; m < num_markers; ++m) {
        if (!on_limb[m]) predicted[m] = nan;
      }
      GatedAssignment found;
      AssignGated(predicted, std::vector<double>(num_markers, gate * factor), free_points, &found);
      std::vector<Eigen::Vector3d> observed(num_markers, nan);
      for (int m = 0; m < num_markers; ++m) {
        if (on_limb[m]) trial[m] = found.point_of_marker[m] >= 0 ? free_index[found.point_of_marker[m]] : -1;
        if (trial[m] >= 0) observed[m] = points[trial[m]];
      }
      FrameSolveReport report;
      Pose solved = trial_pose;
      if (solver->Solve(observed, &solved, &report).ok() && report.usable) trial_pose = solved;
    }
    const double cost = SolvedCost(skeleton, markers, points, trial, gate, solver, &trial_pose);
    if (cost < keep_ratio * best) {
      best = cost, *pose = trial_pose, matches->point_of_marker = trial, changed = true;
    }
  }
  return changed;
}

double SolvedCost(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                  const std::vector<int>& point_of_marker, double gate, MarkerFrameSolver* solver, Pose* pose) {
  const int num_markers = markers.num_markers();
  std::vector<Eigen::Vector3d> observed(num_markers, Eigen::Vector3d::Constant(std::nan("")));
  for (int m = 0; m < num_markers; ++m) {
    if (point_of_marker[m] >= 0) observed[m] = points[point_of_marker[m]];
  }
  FrameSolveReport report;
  Pose solved = *pose;
  if (solver->Solve(observed, &solved, &report).ok() && report.usable) *pose = solved;
  const std::vector<Eigen::Vector3d> model = ModelMarkerPositions(skeleton, markers, *pose);
  double cost = 0.0;
  for (int m = 0; m < num_markers; ++m) {
    cost += point_of_marker[m] >= 0 ? std::min((observed[m] - model[m]).squaredNorm(), gate * gate) : gate * gate;
  }
  return cost;
}

bool PolishMatches(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<Eigen::Vector3d>& points,
                   double gate, bool rematch, bool free_points, double keep_ratio, MarkerFrameSolver* solver,
                   Pose* pose, GatedAssignment* matches) {
  const int num_markers = markers.num_markers();
  std::vector<int> current = matches->point_of_marker;
  double best = SolvedCost(skeleton, markers, points, current, gate, solver, pose);
  const double radius2 = 9.0 * gate * gate;
  // Where each marker is: its point, or its model position when it has none.
  const std::vector<Eigen::Vector3d> model = ModelMarkerPositions(skeleton, markers, *pose);
  const auto where = [&](int m) -> const Eigen::Vector3d& { return current[m] >= 0 ? points[current[m]] : model[m]; };
  const auto near = [&](int m, int n) { return (where(m) - where(n)).squaredNorm() < radius2; };
  const auto close = [&](int m, int n) { return (where(m) - where(n)).squaredNorm() < 4.0 * gate * gate; };
  // Moves: markers that each take another point (-1: none), another marker's or a free one.
  std::vector<char> used(points.size(), 0);
  for (int m = 0; m < num_markers; ++m) {
    if (current[m] >= 0) used[current[m]] = 1;
  }
  std::vector<std::vector<std::pair<int, int>>> moves;
  for (int m = 0; m < num_markers; ++m) {
    for (int n = m + 1; n < num_markers; ++n) {
      if (!near(m, n) || (current[m] < 0 && current[n] < 0) || (!free_points && (current[m] < 0 || current[n] < 0))) {
        continue;
      }
      moves.push_back({{m, current[n]}, {n, current[m]}});
      for (int o = n + 1; o < num_markers; ++o) {
        if (!close(m, n) || !close(m, o) || !close(n, o)) continue;
        moves.push_back({{m, current[n]}, {n, current[o]}, {o, current[m]}});
        moves.push_back({{m, current[o]}, {o, current[n]}, {n, current[m]}});
      }
    }
    for (size_t q = 0; q < points.size() && free_points; ++q) {
      if (used[q] || (points[q] - where(m)).squaredNorm() >= radius2) continue;
      moves.push_back({{m, static_cast<int>(q)}});
      for (int n = 0; n < num_markers; ++n) {
        if (n != m && near(m, n)) moves.push_back({{m, static_cast<int>(q)}, {n, current[m]}});
      }
    }
  }
  for (int pass = 0; pass < 5; ++pass) {
    bool improved = false;
    for (const auto& move : moves) {
      std::vector<int> trial = current;
      for (const auto& [marker, point] : move) trial[marker] = point;
      std::vector<int> count(points.size(), 0);
      bool valid = true;
      for (int m = 0; m < num_markers && valid; ++m) valid = trial[m] < 0 || ++count[trial[m]] == 1;
      if (!valid) continue;
      Pose trial_pose = *pose;
      const double cost = SolvedCost(skeleton, markers, points, trial, gate, solver, &trial_pose);
      if (cost < keep_ratio * best) best = cost, current = trial, *pose = trial_pose, improved = true;
    }
    if (!improved) break;
  }
  const bool changed = current != matches->point_of_marker;
  if (rematch) {
    std::vector<double> gates(num_markers, gate);
    AssignGated(ModelMarkerPositions(skeleton, markers, *pose), gates, points, matches);
  } else {
    matches->point_of_marker = current;
  }
  return changed;
}

void JointShapeErrors(const MarkerSet& markers, const std::vector<std::vector<Eigen::Vector3d>>& points,
                      const std::vector<std::vector<int>>& kept, const std::vector<std::vector<int>>& moved,
                      const std::vector<char>& involved, double* kept_error, double* moved_error) {
  const int num_markers = markers.num_markers();
  const auto joint_of = [&](int m) {
    const auto& attachments = markers.marker(m).attachments;
    return attachments.size() == 1 ? attachments[0].joint : -1;
  };
  *kept_error = *moved_error = 0.0;
  for (int m = 0; m < num_markers; ++m) {
    if (joint_of(m) < 0) continue;
    for (int n = m + 1; n < num_markers; ++n) {
      if (joint_of(n) != joint_of(m) || !(involved[m] || involved[n])) continue;
      const double model = (markers.marker(m).attachments[0].offset - markers.marker(n).attachments[0].offset).norm();
      double kept_sum = 0.0, moved_sum = 0.0;
      int count = 0;
      for (size_t i = 0; i < points.size(); ++i) {
        const int a = kept[i][m], b = kept[i][n], c = moved[i][m], d = moved[i][n];
        if (a < 0 || b < 0 || c < 0 || d < 0) continue;
        kept_sum += std::pow((points[i][a] - points[i][b]).norm() - model, 2);
        moved_sum += std::pow((points[i][c] - points[i][d]).norm() - model, 2);
        ++count;
      }
      if (count > 0) *kept_error += std::sqrt(kept_sum / count), *moved_error += std::sqrt(moved_sum / count);
    }
  }
}

std::vector<Eigen::Vector3d> ModelMarkerPositions(const Skeleton& skeleton, const MarkerSet& markers,
                                                  const Pose& pose) {
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  std::vector<Eigen::Vector3d> out(markers.num_markers());
  for (int m = 0; m < markers.num_markers(); ++m) out[m] = markers.Position(m, fk);
  return out;
}

std::vector<RigidCluster> RigidClusters(const MarkerSet& markers) {
  std::map<int, RigidCluster> by_joint;
  for (int m = 0; m < markers.num_markers(); ++m) {
    const MarkerSpec& spec = markers.marker(m);
    if (spec.attachments.size() != 1) continue;
    RigidCluster& cluster = by_joint[spec.attachments[0].joint];
    cluster.joint = spec.attachments[0].joint;
    cluster.markers.push_back(m);
    cluster.offsets.push_back(spec.attachments[0].offset);
  }
  std::vector<RigidCluster> out;
  for (auto& [joint, cluster] : by_joint) {
    if (cluster.markers.size() >= 3) out.push_back(std::move(cluster));
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const RigidCluster& a, const RigidCluster& b) { return a.markers.size() > b.markers.size(); });
  return out;
}

Acquisition AcquireBody(const Skeleton& skeleton, const MarkerSet& markers, const std::vector<RigidCluster>& clusters,
                        const Pose& start, const std::vector<Eigen::Vector3d>& points,
                        const AcquisitionOptions& options, MarkerFrameSolver* solver) {
  std::vector<Pose> placements;
  const int num_clusters = std::min<int>(options.max_clusters, clusters.size());
  for (int c = 0; c < num_clusters; ++c) {
    for (const Placement& p : ClusterPlacements(clusters[c], points, options)) {
      placements.push_back(PlaceBody(skeleton, start, p.joint, p.world_from_joint));
    }
  }
  if (!points.empty()) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& u : points) centre += u;
    centre /= static_cast<double>(points.size());
    FkData fk(skeleton);
    ForwardKinematics(skeleton, start, &fk);
    for (const Eigen::Matrix3d& axes : AllAxisRotations()) {
      Eigen::Isometry3d world_from_root = Eigen::Isometry3d::Identity();
      world_from_root.linear() = axes * fk.world_rotations[0].toRotationMatrix();
      world_from_root.translation() = centre;
      placements.push_back(PlaceBody(skeleton, start, 0, world_from_root));
    }
  }
  Acquisition best;
  double best_score = std::numeric_limits<double>::infinity();
  for (Pose& pose : placements) {
    GatedAssignment matches;
    const double score = RefinePlacement(skeleton, markers, points, options, solver, &pose, &matches);
    if (score < best_score) best_score = score, best.pose = pose, best.matches = matches;
  }
  best.placements = static_cast<int>(placements.size());
  for (int round = 0; round < 2 && !best.matches.point_of_marker.empty(); ++round) {
    const std::vector<int> before = best.matches.point_of_marker;
    RestartLimbs(skeleton, markers, points, start, options.gate, 0.99, solver, &best.pose, &best.matches);
    PolishMatches(skeleton, markers, points, options.gate, true, true, 0.99, solver, &best.pose, &best.matches);
    if (best.matches.point_of_marker == before) break;
    AcquisitionOptions final_gate = options;
    final_gate.iterations = 1;
    RefinePlacement(skeleton, markers, points, final_gate, solver, &best.pose, &best.matches);
  }
  double sum = 0.0;
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (best.matches.point_of_marker.empty() || best.matches.point_of_marker[m] < 0) continue;
    ++best.matched;
    sum += best.matches.distance[m] * best.matches.distance[m];
  }
  best.rms = best.matched > 0 ? std::sqrt(sum / best.matched) : 0.0;
  best.found = best.matched >= options.accept_fraction * markers.num_markers() && best.matched >= 3 &&
               best.rms <= options.max_rms;
  if (best.pose.rotations.empty()) best.pose = start;
  return best;
}

}  // namespace mocapsolve
