// A character's retarget quality (problems/retarget/retarget_quality.h) as the reports and
// the console show it: the `quality` object of the retarget report, of each character in
// the take report and of each row of `evaluate --method=retarget`, and a one-line summary.
#ifndef MOCAPSOLVE_PIPELINE_RETARGET_QUALITY_REPORT_H_
#define MOCAPSOLVE_PIPELINE_RETARGET_QUALITY_REPORT_H_

#include <string>
#include <vector>

#include "io/json_writer.h"
#include "problems/retarget/retarget_quality.h"

namespace mocapsolve {

// {"limb_mean_deg", "limb_p95_deg", "alignment_deg", "pelvis_orientation_mean_deg",
// "pelvis_orientation_p95_deg", "chest_orientation_mean_deg", "chest_orientation_p95_deg"
// (null when not measured), "limbs": [{"limb", "mean_deg", "p95_deg",
// "tracked_vertices"}], "foot_skate_cm_per_s", "penetration_cm", "penetration_frame_share",
// "self_joint_error_mean_cm", "self_joint_error_max_cm" (null
// unless the own skeleton), "coverage": {part: vertices}, "min_limb_vertices",
// "least_covered_limb", "pass", "failures"} (NaN as null).
JsonObject RetargetQualityJson(const RetargetQuality& quality, const std::vector<std::string>& failures);

// "limbs 4.2 deg mean, 9.8 deg p95; skate 0.31 cm/s; penetration 0.4 cm; fewest limb vertices 12 (left_shin)";
// "; pelvis 3.1 deg p95, chest 6.0 deg p95" when measured.
std::string RetargetQualityLine(const RetargetQuality& quality);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_PIPELINE_RETARGET_QUALITY_REPORT_H_
