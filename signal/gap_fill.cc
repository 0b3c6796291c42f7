#include "signal/gap_fill.h"

#include <algorithm>
#include <string>

namespace mocapsolve {
namespace {

// Offset D = X - R at the edge frame f, and its per-frame velocity: the slope of the
// least-squares line through D at up to `samples` consecutive frames f, f + step, ...
// valid in both paths (step = -1 before the gap, +1 after), zero with one sample. With
// two samples this is the thesis' one-sided difference; more average out the noise of
// a jittery marker, whose one-sided difference, scaled by the gap's length in the
// Hermite tangent, would throw the fill far off (issue 16).
void EdgeOffset(const MarkerTrajectories& x, const MarkerTrajectories& r, int m, int f, int step,
                int samples, double clamp, Eigen::Vector3d* offset, Eigen::Vector3d* velocity) {
  *offset = x.position(f, m) - r.position(f, m);
  velocity->setZero();
  // Sums for the line D(t) = a + b t with t = frames from f (0, 1, 2, ... outward).
  double st = 0.0, stt = 0.0;
  Eigen::Vector3d sd = Eigen::Vector3d::Zero(), std_sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int k = 0; k < samples; ++k) {
    const int g = f + k * step;
    if (g < 0 || g >= x.num_frames() || !x.valid(g, m) || !r.valid(g, m)) break;
    const Eigen::Vector3d d = x.position(g, m) - r.position(g, m);
    st += k;
    stt += double(k) * k;
    sd += d;
    std_sum += k * d;
    ++n;
  }
  if (n >= 2) {
    const Eigen::Vector3d outward_slope = (n * std_sum - st * sd) / (n * stt - st * st);
    // Along increasing time: outward is backward in time before the gap.
    *velocity = step < 0 ? Eigen::Vector3d(-outward_slope) : outward_slope;
  }
  *velocity = velocity->cwiseMax(-clamp).cwiseMin(clamp);
}

}  // namespace

std::vector<Gap> FindGaps(const MarkerTrajectories& markers) {
  std::vector<Gap> gaps;
  for (int m = 0; m < markers.num_markers(); ++m) {
    for (int f = 0; f < markers.num_frames(); ++f) {
      if (markers.valid(f, m)) continue;
      Gap gap{m, f, f};
      while (gap.last + 1 < markers.num_frames() && !markers.valid(gap.last + 1, m)) ++gap.last;
      gaps.push_back(gap);
      f = gap.last;
    }
  }
  return gaps;
}

Status FillGapFromReference(const Gap& gap, const MarkerTrajectories& reference,
                            const GapFillOptions& options, MarkerTrajectories* markers) {
  const int n = markers->num_frames();
  if (reference.num_frames() != n || reference.num_markers() != markers->num_markers()) {
    return Status::Error("gap fill: reference has " + std::to_string(reference.num_frames()) +
                         " frames x " + std::to_string(reference.num_markers()) + " markers, markers " +
                         std::to_string(n) + " x " + std::to_string(markers->num_markers()));
  }
  if (gap.first < 0 || gap.last >= n || gap.first > gap.last || gap.marker < 0 ||
      gap.marker >= markers->num_markers()) {
    return Status::Error("gap fill: gap out of range");
  }
  const int m = gap.marker;
  const bool has_before = gap.first > 0, has_after = gap.last + 1 < n;
  for (int f = std::max(0, gap.first - 1); f <= std::min(n - 1, gap.last + 1); ++f) {
    if (!reference.valid(f, m)) {
      return Status::Error("gap fill: reference marker '" + reference.label(m) + "' is missing at frame " +
                           std::to_string(f));
    }
  }
  const double clamp = options.velocity_clamp;
  Eigen::Vector3d d0 = Eigen::Vector3d::Zero(), v0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d d1 = Eigen::Vector3d::Zero(), v1 = Eigen::Vector3d::Zero();
  if (has_before) EdgeOffset(*markers, reference, m, gap.first - 1, -1, options.edge_samples, clamp, &d0, &v0);
  if (has_after) EdgeOffset(*markers, reference, m, gap.last + 1, +1, options.edge_samples, clamp, &d1, &v1);
  if (!has_after) {  // Runs to the end: hold the offset.
    d1 = d0;
    v1.setZero();
  }
  if (!has_before) {  // Starts the take.
    d0 = d1;
    v0.setZero();
  }
  // Hermite over the span between the edge frames, s = gap.first - 1 .. e = gap.last + 1
  // (span in frames; tangents scaled by it).
  const double t0 = gap.first - 1.0, span = gap.length() + 1.0;
  for (int f = gap.first; f <= gap.last; ++f) {
    const double u = (f - t0) / span;
    const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
    const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
    const Eigen::Vector3d offset = h00 * d0 + h10 * span * v0 + h01 * d1 + h11 * span * v1;
    markers->SetSample(f, m, reference.position(f, m) + offset);
  }
  return Status::Ok();
}

}  // namespace mocapsolve
