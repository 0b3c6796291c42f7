#include "problems/marker_solve/associated_marker_set.h"

#include <map>

#include "kinematics/forward_kinematics.h"
#include "kinematics/motion.h"
#include "problems/marker_solve/marker_observations.h"
#include "problems/marker_solve/subject_checks.h"
#include "problems/retarget/humanoid_roles.h"

namespace mocapsolve {
namespace {

// The middle of joint j's longest bone segment, in j's frame (its origin for a point).
Eigen::Vector3d BoneMiddle(const Skeleton& skeleton, int j) {
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  double longest = -1.0;
  for (const auto& [a, b] : BoneSegments(skeleton, j)) {
    if ((b - a).norm() > longest) longest = (b - a).norm(), best = 0.5 * (a + b);
  }
  return best;
}

// The template joint of an association role; the toes' markers ride on the foot, a chest
// missing falls back on the last spine joint.
int RoleJoint(const HumanoidRoles& roles, const std::string& role) {
  int joint = roles.Find(role);
  if (joint < 0 && role == "chest") {
    for (int k = 9; k >= 1 && joint < 0; --k) joint = roles.Find("spine_" + std::to_string(k));
  }
  return joint;
}

}  // namespace

Status MakeAssociatedMarkerSet(const Skeleton& templ, const MarkerAssociation& association, double min_confidence,
                               AssociatedMarkerSet* out) {
  *out = AssociatedMarkerSet();
  FkData fk(templ);
  ForwardKinematics(templ, RestPose(templ), &fk);
  const HumanoidRoles roles = FindHumanoidRoles(templ, fk.world_positions);
  if (!roles.humanoid) return Status::Error("the template skeleton is no humanoid: " + roles.why_not);
  const int pelvis = roles.Find("pelvis"), head = roles.Find("head");
  if (pelvis < 0 || head < 0) return Status::Error("the template skeleton has no pelvis or head joint");
  const Eigen::Vector3d up = fk.world_positions[head] - fk.world_positions[pelvis];
  Eigen::Index model_axis = 0;
  up.cwiseAbs().maxCoeff(&model_axis);
  Eigen::Vector3d model_up = Eigen::Vector3d::Zero(), file_up = Eigen::Vector3d::Zero();
  model_up[model_axis] = up[model_axis] > 0.0 ? 1.0 : -1.0;
  file_up[association.up_axis] = association.up_sign;
  for (const Eigen::Matrix3d& r : AllAxisRotations()) {
    if ((r * file_up - model_up).norm() < 1e-9) {
      out->axes = AxesName(r);
      break;
    }
  }
  // The pelvis' markers anchor round 0 (the root: without them it is placed by the limbs and
  // the chest alone, and can start tilted): they take half the bar. A walking pelvis moves
  // nearly rigidly with the chest, which lowers its cluster's separation (the confidence),
  // not its role: 02_01's four pelvis markers at 0.48-0.58 were all left out of round 0,
  // whose fit then kept the torso 19.7 degrees off.
  constexpr double kPelvisShare = 0.5;
  // A segment none of whose markers reaches the bar keeps its most confident one: a segment
  // round 0 leaves unobserved is fitted at the template's rest, and the first attach round
  // then places its markers against that pose, anywhere (squat's Davis cut: the feet at
  // confidence 0-0.41, each foot's markers on the femur, the shin or the other foot's toes).
  std::map<std::string, const AssociatedMarker*> segment_best;
  for (const AssociatedMarker& m : association.markers) {
    if (m.role.empty() || RoleJoint(roles, m.role) < 0) continue;
    const AssociatedMarker*& best = segment_best[m.role];
    if (best == nullptr || m.confidence > best->confidence) best = &m;
  }
  for (const AssociatedMarker& m : association.markers) {
    if (!m.role.empty() && m.confidence >= (m.role == "pelvis" ? kPelvisShare : 1.0) * min_confidence) {
      segment_best[m.role] = nullptr;  // The segment is observed by a marker at the bar.
    }
  }
  for (const AssociatedMarker& m : association.markers) {
    // The torso check's groups: every head and pelvis marker (the attach rounds attach the
    // ones round 0 leaves out).
    if (m.role == "head") out->head_labels.push_back(m.label);
    if (m.role == "pelvis") out->pelvis_labels.push_back(m.label);
    const int joint = m.role.empty() ? -1 : RoleJoint(roles, m.role);
    const bool segments_best = !m.role.empty() && segment_best.count(m.role) != 0 && segment_best[m.role] == &m;
    if (joint < 0 || (m.confidence < (m.role == "pelvis" ? kPelvisShare : 1.0) * min_confidence && !segments_best)) {
      out->left_out.push_back(m.label);
      continue;
    }
    MarkerSpec spec;
    spec.label = m.label;
    spec.attachments.push_back({joint, 1.0, BoneMiddle(templ, joint)});
    out->specs.push_back(spec);
    out->joints.push_back(templ.name(joint));
  }
  if (out->specs.size() < 3) return Status::Error("fewer than 3 markers associated with the template's segments");
  return Status::Ok();
}

}  // namespace mocapsolve
