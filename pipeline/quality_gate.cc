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

bool QualityGate::IsValid(std::string* error) const {
  for (double value : {max_naive_rms_mm, max_repaired_rms_mm, max_repaired_share, max_iteration_limit_share,
                       max_marker_offset_cm, max_torso_error_deg}) {
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

}  // namespace mocapsolve
