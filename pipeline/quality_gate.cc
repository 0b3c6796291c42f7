#include "pipeline/quality_gate.h"

#include <cmath>
#include <cstdio>

namespace mocapsolve {
namespace {

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3g", value);
  return text;
}

}  // namespace

const OptionGroup<QualityGate>& QualityGateOptions() {
  using G = QualityGate;
  static const OptionGroup<G>* const group = &(*new OptionGroup<G>())
      .Add(&G::max_naive_rms_mm, "gate_naive_rms_mm", "mm",
           "Quality gate: the plain solve's marker RMS (mm) at most this (a marker set that does not fit the actor "
           "shows here); 0 = no check.")
      .Add(&G::max_repaired_rms_mm, "gate_repaired_rms_mm", "mm",
           "Quality gate: the repaired solve's marker RMS (mm) at most this; 0 = no check.")
      .Add(&G::max_repaired_share, "gate_repaired_share", "",
           "Quality gate: at most this share of the subject's marker samples repaired; 0 = no check.")
      .Add(&G::max_iteration_limit_share, "gate_iteration_limit_share", "",
           "Quality gate: at most this share of frames whose solve stopped at --max_iterations; 0 = no check.")
      .Add(&G::max_marker_offset_cm, "gate_marker_offset_cm", "cm",
           "Quality gate: no marker of the subject farther than this (cm) from its bone (skin distance; CMU "
           "subject 2's own calibration puts RBAC 20.7 cm from upperback); 0 = no check.")
      .Add(&G::max_torso_error_deg, "gate_torso_deg", "degrees",
           "Quality gate: the solved pelvis-to-head direction within this (degrees, mean over the take) of the "
           "head and pelvis markers' own; 0 = no check.")
      .Add(&G::max_limb_mean_deg, "gate_limb_mean_deg", "degrees",
           "Quality gate, per character: the eight limbs' direction error against the source (after one constant "
           "rotation), mean over the limbs, at most this (degrees; the default fails visibly other motion, the "
           "retarget's target is 10); 0 = no check.")
      .Add(&G::max_limb_p95_deg, "gate_limb_p95_deg", "degrees",
           "Quality gate, per character: the limbs' direction error, 95th percentile over limbs and frames, at most "
           "this (degrees; the target is 20); 0 = no check.")
      .Add(&G::max_pelvis_p95_deg, "gate_pelvis_p95_deg", "degrees",
           "Quality gate, per character: the pelvis's rotation against the source's, from their upright rest "
           "poses, 95th percentile over frames, at most this (degrees; a torso carried tilted shows here, not in "
           "the limbs); 0 = no check.")
      .Add(&G::max_foot_skate_cm_s, "gate_foot_skate_cm_s", "cm/s",
           "Quality gate, per character: planted feet's horizontal speed while the source's are in contact at most "
           "this (cm/s); 0 = no check.")
      .Add(&G::max_penetration_cm, "gate_penetration_cm", "cm",
           "Quality gate, per character: no foot joint deeper under the floor than this (cm, below its rest "
           "clearance); 0 = no check.")
      .Add(&G::max_self_joint_error_cm, "gate_self_joint_cm", "cm",
           "Quality gate, per character: where the source is the character's own skeleton, no joint farther than "
           "this (cm) from the source's; 0 = no check.")
      .Add(&G::min_limb_vertices, "gate_limb_vertices", "vertices",
           "Quality gate, per character: every limb (upper arms, forearms, thighs, shins) tracked by at least this "
           "many vertices; 0 = no check.", 0);
  return *group;
}

bool QualityGate::IsValid(std::string* error) const {
  for (double value : {max_naive_rms_mm, max_repaired_rms_mm, max_repaired_share, max_iteration_limit_share,
                       max_marker_offset_cm, max_torso_error_deg, max_limb_mean_deg, max_limb_p95_deg,
                       max_pelvis_p95_deg, max_foot_skate_cm_s, max_penetration_cm, max_self_joint_error_cm}) {
    if (!std::isfinite(value)) {
      *error = "quality gate: thresholds must be finite";
      return false;
    }
  }
  return true;
}

QualityVerdict CheckQuality(const QualityGate& gate, const QualityFigures& figures) {
  QualityVerdict verdict;
  auto check = [&](bool on, double value, double limit, const std::string& what, const char* unit,
                   double shown = 1.0) {
    // A NaN figure fails (NaN <= limit is false): a figure that could not be measured cannot pass.
    if (!on || value <= limit) return;
    verdict.pass = false;
    verdict.failures.push_back(std::string(what) + " " + Number(value * shown) + unit + " > " +
                               Number(limit * shown) + unit);
  };
  check(gate.max_naive_rms_mm > 0, figures.naive_rms_mm, gate.max_naive_rms_mm, "naive marker RMS", " mm");
  check(gate.max_repaired_rms_mm > 0, figures.repaired_rms_mm, gate.max_repaired_rms_mm, "repaired marker RMS",
        " mm");
  check(gate.max_repaired_share > 0 && gate.max_repaired_share < 1, figures.repaired_share,
        gate.max_repaired_share, "repaired samples", " %", 100.0);
  check(gate.max_iteration_limit_share > 0 && gate.max_iteration_limit_share < 1, figures.iteration_limit_share,
        gate.max_iteration_limit_share, "frames at the iteration limit", " %", 100.0);
  check(gate.max_marker_offset_cm > 0, figures.max_marker_offset_cm, gate.max_marker_offset_cm,
        "largest marker-bone distance (" + figures.farthest_marker + ")", " cm");
  // Not measured (no head or pelvis markers): nothing to check.
  check(gate.max_torso_error_deg > 0 && !std::isnan(figures.torso_error_deg), figures.torso_error_deg,
        gate.max_torso_error_deg, "torso direction error", " deg");
  return verdict;
}

std::string RetargetGateNames() {
  return "gate_limb_mean_deg,gate_limb_p95_deg,gate_pelvis_p95_deg,gate_foot_skate_cm_s,gate_penetration_cm,"
         "gate_self_joint_cm,"
         "gate_limb_vertices";
}

void CheckRetargetQuality(const QualityGate& gate, const RetargetQuality& quality, const std::string& who,
                          QualityVerdict* verdict) {
  auto check = [&](bool on, double value, double limit, const std::string& what, const char* unit) {
    if (!on || std::isnan(value) || value <= limit) return;
    verdict->pass = false;
    verdict->failures.push_back(who + ": " + what + " " + Number(value) + unit + " > " + Number(limit) + unit);
  };
  check(gate.max_limb_mean_deg > 0, quality.limb_mean_deg, gate.max_limb_mean_deg, "limb direction error (mean)",
        " deg");
  check(gate.max_limb_p95_deg > 0, quality.limb_p95_deg, gate.max_limb_p95_deg, "limb direction error (95th pct)",
        " deg");
  check(gate.max_pelvis_p95_deg > 0, quality.pelvis_orientation_p95_deg, gate.max_pelvis_p95_deg,
        "pelvis orientation error (95th pct)", " deg");
  check(gate.max_foot_skate_cm_s > 0, quality.foot_skate_cm_s, gate.max_foot_skate_cm_s, "planted foot skate",
        " cm/s");
  check(gate.max_penetration_cm > 0, quality.penetration_cm, gate.max_penetration_cm, "ground penetration", " cm");
  check(gate.max_self_joint_error_cm > 0, quality.self_joint_error_max_cm, gate.max_self_joint_error_cm,
        "joint error on its own skeleton", " cm");
  if (gate.min_limb_vertices > 0 && !quality.least_covered_limb.empty() && quality.min_limb_vertices < gate.min_limb_vertices) {
    verdict->pass = false;
    verdict->failures.push_back(who + ": " + quality.least_covered_limb + " tracked by " +
                                std::to_string(quality.min_limb_vertices) + " vertices < " +
                                std::to_string(gate.min_limb_vertices));
  }
}

}  // namespace mocapsolve
