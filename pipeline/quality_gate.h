// The quality gate: does a take's result deserve to go on without a person looking?
// Every take's report states pass or fail against thresholds; `pipeline` exits 3 on a
// failed gate (its outputs are still written, flagged in the report).
//
// The figures are chosen so that a low residual cannot hide a wrong result:
//   naive marker RMS      the plain per-frame solve on the raw markers (mm): a subject
//                         whose marker set does not fit the actor shows here first
//                         (CMU 02_05 with another subject's set: ~50 mm; with its own: ~8);
//   repaired marker RMS   the final solve on the repaired markers (mm);
//   repaired share        repaired samples / all samples of the subject's markers: a
//                         repair that rewrites much of the take is rebuilding, not cleaning;
//   iteration-limit share frames whose solve stopped at the iteration limit;
//   marker-bone distance  the subject's largest marker-to-bone distance (cm; skin
//                         distance, problems/marker_solve/subject_checks.h): a fit that
//                         bought its residual with absurd offsets;
//   torso direction       the solved pelvis-to-head direction against the markers' own
//                         (mean angle over the take, degrees): a skeleton solved tilted or
//                         upside down while the markers stand upright. Takes without
//                         head and pelvis markers by their usual labels are not checked.
// Per character retargeted (problems/retarget/retarget_quality.h; CheckRetargetQuality):
//   limb directions       the eight limbs' direction error against the source after one
//                         constant rotation: the mean over limbs and the 95th percentile of
//                         all samples (degrees);
//   pelvis orientation    the pelvis's rotation against the source's from their upright rest
//                         poses, 95th percentile over frames (degrees; retarget_quality.h's
//                         torso orientation; not measured for a source with its own mesh);
//   foot skate            planted feet's horizontal speed while the source's are in
//                         contact (cm/s);
//   penetration           the deepest foot joint under the floor (cm);
//   self joint error      where the source is the character's own skeleton, the largest
//                         joint position error (cm);
//   coverage              the fewest tracked vertices on a limb: a limb tracked by fewer
//                         than this follows nothing (a character whose parts are rigid
//                         meshes under bones, with only the hands skinned).
// A threshold <= 0 (or, for shares, >= 1) turns that check off.
#ifndef MOCAPSOLVE_PIPELINE_QUALITY_GATE_H_
#define MOCAPSOLVE_PIPELINE_QUALITY_GATE_H_

#include <string>
#include <vector>

#include "problems/retarget/retarget_quality.h"
#include "settings/option.h"

namespace mocapsolve {

struct QualityGate {
  double max_naive_rms_mm = 30.0;
  double max_repaired_rms_mm = 20.0;
  double max_repaired_share = 0.25;
  double max_iteration_limit_share = 0.2;
  double max_marker_offset_cm = 25.0;
  double max_torso_error_deg = 15.0;
  // Limb directions: the gate fails motion that is visibly other (28-60 degrees on the
  // cgspeed BVH takes onto some characters, RobotExpressive); the retarget's own target,
  // 10 and 20, is measured in BENCHMARKS.md.
  double max_limb_mean_deg = 20.0;
  double max_limb_p95_deg = 40.0;
  // The pelvis's orientation: the shared pairs give <= 16 degrees at the 95th percentile,
  // the tilt of issue 29 (a full rest rotation from the pelvis's children) 23-143
  // (BENCHMARKS.md, "Any character").
  double max_pelvis_p95_deg = 30.0;
  double max_foot_skate_cm_s = 1.0;
  double max_penetration_cm = 1.0;
  double max_self_joint_error_cm = 0.1;
  int min_limb_vertices = 3;

  bool IsValid(std::string* error) const;
};

struct QualityFigures {
  double naive_rms_mm = 0.0;
  double repaired_rms_mm = 0.0;
  double repaired_share = 0.0;
  double iteration_limit_share = 0.0;
  double max_marker_offset_cm = 0.0;
  double torso_error_deg = 0.0;  // NaN: not measured (no head or pelvis markers).
  std::string farthest_marker;   // "LFIN on lhand": where max_marker_offset_cm was measured.
};

struct QualityVerdict {
  bool pass = true;
  // One line per failed check: "repaired marker RMS 23.1 mm > 20 mm".
  std::vector<std::string> failures;
};

QualityVerdict CheckQuality(const QualityGate& gate, const QualityFigures& figures);

// The retarget checks above for one character's figures, added to *verdict as
// "<who>: limb direction error 23.4 deg > 10 deg". A figure not measured (NaN: no limbs,
// not the own skeleton) is not checked, nor coverage on a target with no limb roles.
void CheckRetargetQuality(const QualityGate& gate, const RetargetQuality& quality, const std::string& who,
                          QualityVerdict* verdict);

// The retarget thresholds alone (evaluate --method=retarget, retarget's report).
std::string RetargetGateNames();

// The thresholds as options, declared once (--gate_naive_rms_mm, ...; the defaults are the
// fields' initializers): pipeline's flags and config keys, Python's pipeline() keywords.
const OptionGroup<QualityGate>& QualityGateOptions();

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_QUALITY_GATE_H_
