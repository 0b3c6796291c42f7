#include "problems/marker_solve/offset_refinement.h"

#include <string>

#include "kinematics/forward_kinematics.h"

namespace mocapsolve {

Status RefineMarkerOffsets(const Skeleton& skeleton, const MarkerSet& calibrated,
                           const std::vector<std::vector<Eigen::Vector3d>>& observed, const Motion& motion,
                           const OffsetRefinementOptions& options, MarkerSet* refined,
                           OffsetRefinementReport* report) {
  if (motion.frames.size() != observed.size()) return Status::Error("offset refinement: motion and markers differ in frames");
  if (!(options.prior_frames >= 0.0) || !(options.max_shift >= 0.0)) {
    return Status::Error("offset refinement: prior_frames and max_shift must be >= 0");
  }
  const int num_markers = calibrated.num_markers();
  for (const std::vector<Eigen::Vector3d>& frame : observed) {
    if (static_cast<int>(frame.size()) != num_markers) return Status::Error("offset refinement: observations do not match the marker set");
  }
  // Sum of local positions and count per marker, over the frames it was seen.
  std::vector<Eigen::Vector3d> sum(num_markers, Eigen::Vector3d::Zero());
  std::vector<int> count(num_markers, 0);
  FkData fk(skeleton);
  for (size_t f = 0; f < observed.size(); ++f) {
    bool any = false;
    for (int m = 0; m < num_markers && !any; ++m) any = observed[f][m].allFinite();
    if (!any) continue;
    ForwardKinematics(skeleton, motion.frames[f], &fk);
    for (int m = 0; m < num_markers; ++m) {
      const MarkerSpec& spec = calibrated.marker(m);
      if (spec.attachments.size() != 1 || !observed[f][m].allFinite()) continue;
      const int j = spec.attachments[0].joint;
      sum[m] += fk.world_rotations[j].conjugate() * (observed[f][m] - fk.world_positions[j]);
      ++count[m];
    }
  }
  std::vector<MarkerSpec> specs;
  if (report != nullptr) *report = OffsetRefinementReport{std::vector<double>(num_markers, 0.0), 0};
  for (int m = 0; m < num_markers; ++m) {
    MarkerSpec spec = calibrated.marker(m);
    if (count[m] > 0) {
      const Eigen::Vector3d z0 = spec.attachments[0].offset;
      Eigen::Vector3d z = (sum[m] + options.prior_frames * z0) / (count[m] + options.prior_frames);
      const double shift = (z - z0).norm();
      if (options.max_shift > 0.0 && shift > options.max_shift) z = z0 + (z - z0) * (options.max_shift / shift);
      spec.attachments[0].offset = z;
      if (report != nullptr) {
        report->shift[m] = (z - z0).norm();
        ++report->refined;
      }
    }
    specs.push_back(std::move(spec));
  }
  return MarkerSet::Create(skeleton, std::move(specs), refined);
}

}  // namespace mocapsolve
