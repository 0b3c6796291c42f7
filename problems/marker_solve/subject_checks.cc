#include "problems/marker_solve/subject_checks.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>

#include <Eigen/Geometry>

#include "kinematics/forward_kinematics.h"
#include "problems/marker_solve/held_segments.h"

namespace mocapsolve {
namespace {

std::string Lower(const std::string& text) {
  std::string out;
  for (char c : text) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Distance from p to segment [a, b] and the nearest point.
Eigen::Vector3d NearestOnSegment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = b - a;
  const double length2 = d.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(d) / length2, 0.0, 1.0) : 0.0;
  return a + t * d;
}

Eigen::Vector3d NearestOnBone(const Skeleton& skeleton, int j, const Eigen::Vector3d& point,
                              const std::vector<bool>& held) {
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double best_distance = (point - best).norm();
  for (const auto& [a, b] : BoneSegments(skeleton, j, held)) {
    const Eigen::Vector3d q = NearestOnSegment(a, b, point);
    const double d = (point - q).norm();
    if (d < best_distance) best_distance = d, best = q;
  }
  return best;
}

// Centroid of the observed markers among `labels` (by the set's labels); false with
// fewer than 2.
bool Centroid(const MarkerSet& markers, const std::vector<Eigen::Vector3d>& observed,
              const std::set<std::string>& labels, Eigen::Vector3d* centroid) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int m = 0; m < markers.num_markers(); ++m) {
    if (labels.count(markers.label(m)) && observed[m].allFinite()) sum += observed[m], ++n;
  }
  if (n < 2) return false;
  *centroid = sum / n;
  return true;
}

int HeadJoint(const Skeleton& skeleton) {
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (Lower(skeleton.name(j)) == "head") return j;
  }
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    const std::string name = Lower(skeleton.name(j));
    if (name.find("head") != std::string::npos && name.find("end") == std::string::npos) return j;
  }
  return -1;
}

}  // namespace

std::string SideFreeName(const std::string& name) {
  const std::string lower = Lower(name);
  for (const std::string p : {"left", "right"}) {
    if (lower.compare(0, p.size(), p) == 0 && lower.size() > p.size()) return lower.substr(p.size());
  }
  if (lower.size() > 1 && (lower[0] == 'l' || lower[0] == 'r')) return lower.substr(1);
  return lower;
}

int MirrorJoint(const Skeleton& skeleton, int j) {
  const char side = static_cast<char>(std::tolower(static_cast<unsigned char>(skeleton.name(j)[0])));
  if (side != 'l' && side != 'r') return -1;
  const std::string key = SideFreeName(skeleton.name(j));
  for (int i = 0; i < skeleton.num_joints(); ++i) {
    const char other = static_cast<char>(std::tolower(static_cast<unsigned char>(skeleton.name(i)[0])));
    if (i != j && other != side && (other == 'l' || other == 'r') && SideFreeName(skeleton.name(i)) == key) {
      return i;
    }
  }
  return -1;
}

std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> BoneSegments(const Skeleton& skeleton, int j,
                                                                      const std::vector<bool>& held) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
  // Depth-first over the rigid body of j: (joint, j_from_joint, reached through a held
  // child: its own held children are not added, one held bone deep).
  struct Part {
    int joint;
    Eigen::Isometry3d frame;
    bool through_held;
  };
  std::vector<Part> stack = {{j, Eigen::Isometry3d::Identity(), false}};
  while (!stack.empty()) {
    const Part part = stack.back();
    stack.pop_back();
    const int k = part.joint;
    const Eigen::Vector3d origin = part.frame.translation();
    bool any = false;
    for (int c = k + 1; c < skeleton.subtree_end(k); ++c) {
      if (skeleton.parent(c) != k) continue;
      segments.emplace_back(origin, part.frame * skeleton.offset(c));
      any = true;
      const bool rigid = skeleton.num_rotation_dofs(c) == 0 && !skeleton.has_translation_channels(c);
      const bool held_child = !rigid && !part.through_held && c < static_cast<int>(held.size()) && held[c];
      if (rigid || held_child) {
        Eigen::Isometry3d child = part.frame;
        child.translate(skeleton.offset(c));
        child.rotate(skeleton.rest_rotation(c));
        stack.push_back({c, child, part.through_held || held_child});
      }
    }
    for (const EndSite& site : skeleton.end_sites()) {
      if (site.parent != k) continue;
      segments.emplace_back(origin, part.frame * site.offset);
      any = true;
    }
    if (!any) segments.emplace_back(origin, origin);
  }
  return segments;
}

double DistanceToBone(const Skeleton& skeleton, int j, const Eigen::Vector3d& point, const std::vector<bool>& held) {
  return (point - NearestOnBone(skeleton, j, point, held)).norm();
}

Eigen::Vector3d ClampToBone(const Skeleton& skeleton, int j, const Eigen::Vector3d& point, double max_distance,
                            const std::vector<bool>& held) {
  const Eigen::Vector3d nearest = NearestOnBone(skeleton, j, point, held);
  const Eigen::Vector3d away = point - nearest;
  const double distance = away.norm();
  if (distance <= max_distance) return point;
  return nearest + away * (max_distance / distance);
}

SubjectChecks CheckSubjectFit(const Skeleton& skeleton, const MarkerSet& markers,
                              const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& motion,
                              const SubjectCheckOptions& options) {
  SubjectChecks checks;
  const double cm = skeleton.unit().known() ? skeleton.unit().metres_per_unit * 100.0 : 1.0;
  char line[256];
  // 1. Skin distance, to the bone with its held limbs' (as the fit clamps it).
  const std::vector<bool> held = HeldLimbJoints(skeleton, markers);
  for (int m = 0; m < markers.num_markers(); ++m) {
    MarkerDistance d;
    d.label = markers.label(m);
    for (const MarkerAttachment& a : markers.marker(m).attachments) {
      const double to_bone = DistanceToBone(skeleton, a.joint, a.offset, held) * cm;
      if (to_bone >= d.to_bone_cm) d.to_bone_cm = to_bone, d.joint = skeleton.name(a.joint);
      d.to_joint_cm = std::max(d.to_joint_cm, a.offset.norm() * cm);
    }
    if (d.to_bone_cm > checks.max_bone_distance_cm) {
      checks.max_bone_distance_cm = d.to_bone_cm;
      checks.farthest_marker = d.label + " on " + d.joint;
    }
    checks.max_joint_distance_cm = std::max(checks.max_joint_distance_cm, d.to_joint_cm);
    checks.markers.push_back(d);
  }
  if (checks.max_bone_distance_cm > options.max_marker_bone_distance_cm) {
    std::string far;
    int count = 0;
    for (const MarkerDistance& d : checks.markers) {
      if (d.to_bone_cm > options.max_marker_bone_distance_cm) ++count;
    }
    std::snprintf(line, sizeof line, "%d marker(s) farther than %.0f cm from their bone (worst %s: %.1f cm)", count,
                  options.max_marker_bone_distance_cm, checks.farthest_marker.c_str(), checks.max_bone_distance_cm);
    checks.failures.push_back(line);
  }
  // 2. Torso direction.
  const int head = HeadJoint(skeleton);
  std::set<std::string> head_labels = {"LFHD", "RFHD", "LBHD", "RBHD"};
  std::set<std::string> pelvis_labels = {"LFWT", "RFWT", "LBWT", "RBWT", "LASI", "RASI", "LPSI", "RPSI"};
  if (!options.head_labels.empty()) head_labels = {options.head_labels.begin(), options.head_labels.end()};
  if (!options.pelvis_labels.empty()) pelvis_labels = {options.pelvis_labels.begin(), options.pelvis_labels.end()};
  if (head > 0) {
    FkData fk(skeleton);
    double sum = 0.0;
    const size_t frames = std::min(observed.size(), motion.frames.size());
    for (size_t f = 0; f < frames; ++f) {
      Eigen::Vector3d top, bottom;
      if (!Centroid(markers, observed[f], head_labels, &top) || !Centroid(markers, observed[f], pelvis_labels, &bottom)) {
        continue;
      }
      ForwardKinematics(skeleton, motion.frames[f], &fk);
      const Eigen::Vector3d solved = fk.world_positions[head] - fk.world_positions[0];
      const Eigen::Vector3d seen = top - bottom;
      if (solved.norm() == 0.0 || seen.norm() == 0.0) continue;
      const double angle = std::acos(std::clamp(solved.normalized().dot(seen.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
      sum += angle;
      checks.torso_error_max_deg = std::max(checks.torso_error_max_deg, angle);
      ++checks.torso_frames;
    }
    if (checks.torso_frames > 0) checks.torso_error_mean_deg = sum / checks.torso_frames;
    if (checks.torso_error_mean_deg > options.max_torso_error_deg) {
      std::snprintf(line, sizeof line,
                    "the solved pelvis-to-head direction is %.1f degrees (mean; max %.1f) off the markers' own "
                    "(limit %.0f)", checks.torso_error_mean_deg, checks.torso_error_max_deg, options.max_torso_error_deg);
      checks.failures.push_back(line);
    }
  }
  // 4. Residual.
  {
    FkData fk(skeleton);
    double sum = 0.0;
    const size_t frames = std::min(observed.size(), motion.frames.size());
    for (size_t f = 0; f < frames; ++f) {
      ForwardKinematics(skeleton, motion.frames[f], &fk);
      for (int m = 0; m < markers.num_markers() && m < static_cast<int>(observed[f].size()); ++m) {
        if (!observed[f][m].allFinite()) continue;
        sum += (markers.Position(m, fk) - observed[f][m]).squaredNorm();
        ++checks.samples;
      }
    }
    checks.rms_mm = checks.samples > 0 ? std::sqrt(sum / checks.samples) * cm * 10.0 : 0.0;
    if (checks.rms_mm > options.max_rms_mm) {
      std::snprintf(line, sizeof line, "marker RMS %.1f mm (limit %.0f mm): the model does not explain the markers",
                    checks.rms_mm, options.max_rms_mm);
      checks.failures.push_back(line);
    }
  }
  // 3. Symmetry.
  double longest = 0.0;
  for (int j = 0; j < skeleton.num_joints(); ++j) longest = std::max(longest, skeleton.offset(j).norm());
  for (int j = 1; j < skeleton.num_joints(); ++j) {
    const int twin = MirrorJoint(skeleton, j);
    if (twin < j) continue;
    const double a = skeleton.offset(j).norm(), b = skeleton.offset(twin).norm();
    if (std::max(a, b) < options.min_symmetry_bone_share * longest) continue;
    const double asymmetry = std::abs(a - b) / std::max(a, b);
    if (asymmetry > checks.max_asymmetry) {
      checks.max_asymmetry = asymmetry;
      checks.least_symmetric_pair = skeleton.name(j) + "/" + skeleton.name(twin);
    }
  }
  if (checks.max_asymmetry > options.max_asymmetry) {
    std::snprintf(line, sizeof line, "left/right bone lengths differ by %.1f %% (%s; limit %.0f %%)",
                  100.0 * checks.max_asymmetry, checks.least_symmetric_pair.c_str(), 100.0 * options.max_asymmetry);
    checks.failures.push_back(line);
  }
  return checks;
}

}  // namespace mocapsolve
