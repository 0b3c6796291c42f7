#include "pipeline/retarget_quality_report.h"

#include <cmath>
#include <cstdio>

namespace mocapsolve {

JsonObject RetargetQualityJson(const RetargetQuality& quality, const std::vector<std::string>& failures) {
  std::vector<JsonObject> limbs;
  for (const LimbDirectionError& limb : quality.limbs) {
    JsonObject o;
    o.Add("limb", limb.limb).Add("mean_deg", limb.mean_deg).Add("p95_deg", limb.p95_deg)
        .Add("tracked_vertices", limb.tracked_vertices);
    limbs.push_back(o);
  }
  JsonObject coverage;
  for (const auto& [part, count] : quality.coverage) coverage.Add(part, count);
  const std::vector<JsonValue> failed(failures.begin(), failures.end());
  JsonObject out;
  out.Add("pass", failures.empty())
      .Add("failures", failed)
      .Add("limb_mean_deg", quality.limb_mean_deg)
      .Add("limb_p95_deg", quality.limb_p95_deg)
      .Add("alignment_deg", quality.alignment_deg)
      .Add("pelvis_orientation_mean_deg", quality.pelvis_orientation_mean_deg)
      .Add("pelvis_orientation_p95_deg", quality.pelvis_orientation_p95_deg)
      .Add("chest_orientation_mean_deg", quality.chest_orientation_mean_deg)
      .Add("chest_orientation_p95_deg", quality.chest_orientation_p95_deg)
      .Add("limbs", limbs)
      .Add("foot_skate_cm_per_s", quality.foot_skate_cm_s)
      .Add("penetration_cm", quality.penetration_cm)
      .Add("penetration_frame_share", quality.penetration_frame_share)
      .Add("self_joint_error_mean_cm", quality.self_joint_error_mean_cm)
      .Add("self_joint_error_max_cm", quality.self_joint_error_max_cm)
      .Add("coverage", coverage)
      .Add("min_limb_vertices", quality.min_limb_vertices)
      .Add("least_covered_limb", quality.least_covered_limb);
  return out;
}

std::string RetargetQualityLine(const RetargetQuality& quality) {
  char text[512];
  std::snprintf(text, sizeof text,
                "limbs %.1f deg mean, %.1f deg p95; skate %.2f cm/s; penetration %.1f cm; fewest limb "
                "vertices %d (%s)",
                quality.limb_mean_deg, quality.limb_p95_deg, quality.foot_skate_cm_s, quality.penetration_cm,
                quality.min_limb_vertices,
                quality.least_covered_limb.empty() ? "none" : quality.least_covered_limb.c_str());
  std::string line = text;
  if (!std::isnan(quality.pelvis_orientation_p95_deg)) {
    std::snprintf(text, sizeof text, "; pelvis %.1f deg p95, chest %.1f deg p95", quality.pelvis_orientation_p95_deg,
                  quality.chest_orientation_p95_deg);
    line += text;
  }
  if (!std::isnan(quality.self_joint_error_max_cm)) {
    std::snprintf(text, sizeof text, "; own skeleton: joint error %.3g cm max", quality.self_joint_error_max_cm);
    line += text;
  }
  return line;
}

}  // namespace mocapsolve
