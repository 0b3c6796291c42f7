#include "problems/marker_solve/synthetic_marker_set.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mocapsolve {
namespace {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64 (Steele, Lea, Flood 2014): a tiny generator with the same stream everywhere.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(Next() >> 11) * (1.0 / 9007199254740992.0);
  }

 private:
  uint64_t state_;
};

}  // namespace

MarkerSet MakeSyntheticMarkerSet(const Skeleton& skeleton, int per_joint, uint32_t seed) {
  const int num_joints = skeleton.num_joints();
  // The longest child offset (bone) of every joint, in the joint's frame.
  std::vector<Eigen::Vector3d> bone(num_joints, Eigen::Vector3d::Zero());
  std::vector<bool> has_child(num_joints, false);
  const auto consider = [&](int parent, const Eigen::Vector3d& offset) {
    if (parent < 0 || parent >= num_joints) return;
    has_child[parent] = true;
    if (offset.norm() > bone[parent].norm()) bone[parent] = offset;
  };
  for (int j = 1; j < num_joints; ++j) consider(skeleton.parent(j), skeleton.offset(j));
  for (const EndSite& site : skeleton.end_sites()) consider(site.parent, site.offset);

  std::vector<double> lengths;
  for (int j = 0; j < num_joints; ++j) {
    if (bone[j].norm() > 0.0) lengths.push_back(bone[j].norm());
  }
  double typical = 1.0;
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    typical = lengths[lengths.size() / 2];
  }

  SplitMix64 random(seed);
  std::vector<MarkerSpec> specs;
  for (int j = 0; per_joint >= 1 && j < num_joints; ++j) {
    if (!has_child[j]) continue;
    Eigen::Vector3d b = bone[j];
    // Zero-length bones: a virtual bone of typical length along +Y; tiny ones count as
    // zero so the perpendicular basis below stays well conditioned.
    if (b.norm() <= 1e-9 * typical) b = Eigen::Vector3d(0.0, typical, 0.0);
    const double length = b.norm();
    const Eigen::Vector3d axis = b / length;
    Eigen::Index least;
    axis.cwiseAbs().minCoeff(&least);
    const Eigen::Vector3d e1 = axis.cross(Eigen::Vector3d::Unit(least)).normalized();
    const Eigen::Vector3d e2 = axis.cross(e1);
    const double theta0 = random.Uniform(0.0, 2.0 * kPi);
    for (int k = 0; k < per_joint; ++k) {
      const double u = random.Uniform(0.2, 0.8);
      const double r = random.Uniform(0.15, 0.35);
      const double jitter = random.Uniform(-20.0, 20.0) * kPi / 180.0;
      const double theta = k < 3 ? theta0 + 2.0 * kPi * k / 3.0 + jitter : random.Uniform(0.0, 2.0 * kPi);
      MarkerAttachment attachment;
      attachment.joint = j;
      attachment.weight = 1.0;
      attachment.offset = u * b + r * length * (std::cos(theta) * e1 + std::sin(theta) * e2);
      specs.push_back({skeleton.name(j) + "_" + std::to_string(k), {attachment}});
    }
  }
  MarkerSet marker_set;
  // Joint names are unique, so labels are; offsets are finite: Create cannot fail.
  if (!MarkerSet::Create(skeleton, std::move(specs), &marker_set).ok()) return MarkerSet();
  return marker_set;
}

}  // namespace mocapsolve
