#include "kinematics/bind_pose_shape.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <vector>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Point {
  Eigen::Vector3d position;
  int joint;  // The joint, or for an end site its parent joint.
};

std::string Lower(const std::string& name) {
  std::string out = name.substr(name.rfind(':') == std::string::npos ? 0 : name.rfind(':') + 1);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool NamedLikeUpperArm(const std::string& name) {
  const std::string n = Lower(name);
  if (n.find("upperarm") != std::string::npos || n.find("upper_arm") != std::string::npos ||
      n.find("humerus") != std::string::npos) {
    return true;
  }
  if (n.find("fore") != std::string::npos || n.find("lower") != std::string::npos) return false;
  const size_t at = n.find("arm");
  return at != std::string::npos && at + 3 == n.size();
}

// Joints from `ancestor` (exclusive) down to `joint` (inclusive).
std::vector<int> ChainBelow(const Skeleton& skeleton, int ancestor, int joint) {
  std::vector<int> chain;
  for (int j = joint; j != ancestor && j >= 0; j = skeleton.parent(j)) chain.push_back(j);
  std::reverse(chain.begin(), chain.end());
  return chain;
}

// The chain continued below its last joint, through the child with the largest subtree
// each time (an arm hanging down ends at the shoulder as the outermost point).
void ExtendChain(const Skeleton& skeleton, std::vector<int>* chain) {
  if (chain->empty()) return;
  std::vector<int> size(skeleton.num_joints(), 1);
  for (int j = skeleton.num_joints() - 1; j > 0; --j) size[skeleton.parent(j)] += size[j];
  for (;;) {
    int best = -1;
    for (int j = chain->back() + 1; j < skeleton.num_joints(); ++j) {
      if (skeleton.parent(j) == chain->back() && (best < 0 || size[j] > size[best])) best = j;
    }
    if (best < 0) return;
    chain->push_back(best);
  }
}

int CommonAncestor(const Skeleton& skeleton, int a, int b) {
  std::vector<bool> above_a(skeleton.num_joints(), false);
  for (int j = a; j >= 0; j = skeleton.parent(j)) above_a[j] = true;
  int j = b;
  while (j >= 0 && !above_a[j]) j = skeleton.parent(j);
  return std::max(j, 0);
}

// The upper arm of a chain (see the header): its first and second joint, or false.
bool UpperArm(const std::vector<int>& chain, const FkData& fk, const Skeleton& skeleton, int* from, int* to) {
  int start = -1;
  for (size_t k = 0; k < chain.size() && start < 0; ++k) {
    if (NamedLikeUpperArm(skeleton.name(chain[k]))) start = static_cast<int>(k);
  }
  if (start < 0) start = chain.size() >= 4 ? 1 : 0;
  const double eps = 1e-9;
  for (size_t k = start + 1; k < chain.size(); ++k) {
    if ((fk.world_positions[chain[k]] - fk.world_positions[chain[start]]).norm() > eps) {
      *from = chain[start];
      *to = chain[k];
      return true;
    }
  }
  return false;
}

double BelowHorizontalDeg(const Eigen::Vector3d& direction, const Eigen::Vector3d& up) {
  const double s = std::clamp(-direction.normalized().dot(up), -1.0, 1.0);
  return std::asin(s) * 180.0 / kPi;
}

Eigen::Vector3d Axis(int axis, int sign) { return sign * Eigen::Vector3d::Unit(axis); }

// The extremes along the wider horizontal axis (for up axis `up`): the hands' candidates.
void ExtremePoints(const std::vector<Point>& points, int up, int* low, int* high) {
  int lateral = (up + 1) % 3;
  const int other = (up + 2) % 3;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Point& p : points) lo = lo.cwiseMin(p.position), hi = hi.cwiseMax(p.position);
  if (hi[other] - lo[other] > hi[lateral] - lo[lateral]) lateral = other;
  *low = *high = 0;
  for (int k = 0; k < static_cast<int>(points.size()); ++k) {
    if (points[k].position[lateral] < points[*low].position[lateral]) *low = k;
    if (points[k].position[lateral] > points[*high].position[lateral]) *high = k;
  }
}

// A pair of arms for up axis `up`: the extremes along the wider horizontal axis, their
// lowest common ancestor (the chest) above the root along +-up, chains from the chest of
// the same joint count and length (within 20 %) on opposite sides at similar heights.
struct ArmPair {
  bool found = false;
  std::string reason;
  std::vector<int> chains[2];
  int up_sign = 1;
};

double ChainLength(const std::vector<int>& chain, int chest, const FkData& fk) {
  double length = 0.0;
  int previous = chest;
  for (int j : chain) length += (fk.world_positions[j] - fk.world_positions[previous]).norm(), previous = j;
  return length;
}

ArmPair FindArms(const Skeleton& skeleton, const FkData& fk, const std::vector<Point>& points, int up) {
  ArmPair pair;
  int low = 0, high = 0;
  ExtremePoints(points, up, &low, &high);
  const int chest = CommonAncestor(skeleton, points[low].joint, points[high].joint);
  double lo = INFINITY, hi = -INFINITY;
  for (const Point& p : points) lo = std::min(lo, p.position[up]), hi = std::max(hi, p.position[up]);
  const Eigen::Vector3d body_up = fk.world_positions[chest] - fk.world_positions[0];
  pair.chains[0] = ChainBelow(skeleton, chest, points[low].joint);
  pair.chains[1] = ChainBelow(skeleton, chest, points[high].joint);
  ExtendChain(skeleton, &pair.chains[0]);
  ExtendChain(skeleton, &pair.chains[1]);
  const double l0 = ChainLength(pair.chains[0], chest, fk), l1 = ChainLength(pair.chains[1], chest, fk);
  if (chest == 0 || pair.chains[0].empty() || pair.chains[1].empty() || pair.chains[0] == pair.chains[1] ||
      !(std::abs(body_up[up]) >= 0.7 * body_up.norm())) {
    pair.reason = "no pair of arms branching off a chest above the root";
  } else if (pair.chains[0].size() != pair.chains[1].size() || !(std::abs(l0 - l1) <= 0.2 * std::max(l0, l1))) {
    pair.reason = "the two sides' outermost chains differ (" + std::to_string(pair.chains[0].size()) + " and " +
                  std::to_string(pair.chains[1].size()) + " joints)";
  } else if (std::abs(points[low].position[up] - points[high].position[up]) > 0.15 * (hi - lo)) {
    pair.reason = "the two sides' outermost points are at different heights";
  } else {
    pair.found = true;
    pair.up_sign = body_up[up] >= 0 ? 1 : -1;
  }
  return pair;
}

}  // namespace

BindPoseShape DescribeBindPose(const Skeleton& skeleton, const Pose& pose, const Eigen::Matrix3Xd& vertices,
                               int file_up_axis) {
  BindPoseShape shape;
  FkData fk(skeleton);
  ForwardKinematics(skeleton, pose, &fk);
  std::vector<Point> points;
  for (int j = 0; j < skeleton.num_joints(); ++j) points.push_back({fk.world_positions[j], j});
  const Vector3dVector ends = EndSitePositions(skeleton, fk);
  for (size_t e = 0; e < ends.size(); ++e) points.push_back({ends[e], skeleton.end_sites()[e].parent});

  // The up axis: the file's first, then the others, until one gives a pair of arms.
  int up = file_up_axis, sign = 1;
  ArmPair pair;
  for (int k = 0; k < 3 && !pair.found; ++k) {
    const int candidate = (file_up_axis + k) % 3;
    ArmPair tried = FindArms(skeleton, fk, points, candidate);
    if (k == 0 || tried.found) pair = tried;
    if (tried.found) up = candidate, sign = tried.up_sign;
  }
  shape.up_axis = up;
  shape.up_sign = sign;
  double lo = INFINITY, hi = -INFINITY;
  if (vertices.cols() > 0) {
    lo = vertices.row(up).minCoeff();
    hi = vertices.row(up).maxCoeff();
    shape.height_from_mesh = true;
  } else {
    for (const Point& p : points) lo = std::min(lo, p.position[up]), hi = std::max(hi, p.position[up]);
  }
  shape.height = points.empty() ? 0.0 : hi - lo;
  if (!pair.found) {
    shape.reason = pair.reason;
    return shape;
  }
  const std::vector<int>* chains = pair.chains;
  const Eigen::Vector3d up_vector = Axis(up, sign);
  for (int side = 0; side < 2 && shape.reason.empty(); ++side) {
    int from = -1, to = -1;
    if (!UpperArm(chains[side], fk, skeleton, &from, &to)) {
      shape.reason = "an arm chain has no bone of non-zero length";
      break;
    }
    shape.upper_arms[side] = skeleton.name(from) + " -> " + skeleton.name(to);
    shape.below_horizontal_deg[side] =
        BelowHorizontalDeg(fk.world_positions[to] - fk.world_positions[from], up_vector);
  }
  if (!shape.reason.empty()) {
    shape.upper_arms[0] = shape.upper_arms[1] = "";
    return shape;
  }
  const double a = shape.below_horizontal_deg[0], b = shape.below_horizontal_deg[1];
  if (std::abs(a) <= 15.0 && std::abs(b) <= 15.0) {
    shape.kind = "T-pose";
  } else if (a > 15.0 && a <= 65.0 && b > 15.0 && b <= 65.0) {
    shape.kind = "A-pose";
  }
  return shape;
}

}  // namespace mocapsolve
