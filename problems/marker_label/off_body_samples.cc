#include "problems/marker_label/off_body_samples.h"

#include <cmath>
#include <limits>

namespace mocapsolve {
namespace {

constexpr double kNoBound = std::numeric_limits<double>::infinity();

// B_mn of the header (kNoBound when the pair has none).
std::vector<std::vector<double>> PairBounds(const Skeleton& skeleton, const MarkerSet& markers) {
  const int num_markers = markers.num_markers();
  // Marker m (on joint a) seen from joint c, an ancestor of a or a itself: its first step
  // in c's frame (the offset of c's child toward a, or z_m when a == c) and the length of
  // the rest of the way (the bones below that child, then |z_m|); false past a joint
  // with animated translation.
  const auto from = [&](int m, int c, Eigen::Vector3d* first, double* rest) {
    const MarkerAttachment& attachment = markers.marker(m).attachments[0];
    if (attachment.joint == c) {
      *first = attachment.offset, *rest = 0.0;
      return true;
    }
    *rest = attachment.offset.norm();
    int j = attachment.joint;
    for (; skeleton.parent(j) != c; j = skeleton.parent(j)) {
      if (skeleton.has_translation_channels(j)) return false;
      *rest += skeleton.offset(j).norm();
    }
    *first = skeleton.offset(j);
    return !skeleton.has_translation_channels(j);
  };
  std::vector<std::vector<double>> bound(num_markers, std::vector<double>(num_markers, kNoBound));
  for (int m = 0; m < num_markers; ++m) {
    if (markers.marker(m).attachments.size() != 1) continue;
    for (int n = m + 1; n < num_markers; ++n) {
      if (markers.marker(n).attachments.size() != 1) continue;
      int c = markers.marker(m).attachments[0].joint;
      while (!skeleton.IsAncestorOrSelf(c, markers.marker(n).attachments[0].joint)) c = skeleton.parent(c);
      Eigen::Vector3d first_m, first_n;
      double rest_m = 0.0, rest_n = 0.0;
      if (!from(m, c, &first_m, &rest_m) || !from(n, c, &first_n, &rest_n)) continue;
      bound[m][n] = bound[n][m] = (first_m - first_n).norm() + rest_m + rest_n;
    }
  }
  return bound;
}

}  // namespace

std::vector<std::vector<char>> OffBodySamples(const Skeleton& skeleton, const MarkerSet& markers,
                                              const std::vector<std::vector<Eigen::Vector3d>>& observed,
                                              double tolerance) {
  const int num_markers = markers.num_markers();
  const std::vector<std::vector<double>> bound = PairBounds(skeleton, markers);
  std::vector<std::vector<char>> off(observed.size(), std::vector<char>(num_markers, 0));
  for (size_t f = 0; f < observed.size(); ++f) {
    const std::vector<Eigen::Vector3d>& x = observed[f];
    // excess[m][n] > 0: the pair is violated by that much.
    std::vector<std::vector<double>> excess(num_markers, std::vector<double>(num_markers, 0.0));
    bool any = false;
    for (int m = 0; m < num_markers; ++m) {
      if (!x[m].allFinite()) continue;
      for (int n = m + 1; n < num_markers; ++n) {
        if (!x[n].allFinite() || bound[m][n] == kNoBound) continue;
        const double e = (x[m] - x[n]).norm() - bound[m][n] - tolerance;
        if (e > 0.0) excess[m][n] = excess[n][m] = e, any = true;
      }
    }
    // Confirmations: joint mates (markers on the same joint) at their model distance.
    std::vector<int> confirmed(num_markers, 0);
    for (int m = 0; m < num_markers && any; ++m) {
      const auto& am = markers.marker(m).attachments;
      if (!x[m].allFinite() || am.size() != 1) continue;
      for (int n = 0; n < num_markers; ++n) {
        const auto& an = markers.marker(n).attachments;
        if (n == m || !x[n].allFinite() || an.size() != 1 || an[0].joint != am[0].joint) continue;
        confirmed[m] += std::abs((x[m] - x[n]).norm() - (am[0].offset - an[0].offset).norm()) <= tolerance;
      }
    }
    while (any) {
      int worst = -1, worst_count = 0;
      double worst_sum = 0.0;
      for (int m = 0; m < num_markers; ++m) {
        if (off[f][m]) continue;
        int count = 0;
        double sum = 0.0;
        for (int n = 0; n < num_markers; ++n) {
          if (!off[f][n] && excess[m][n] > 0.0) ++count, sum += excess[m][n];
        }
        if (count == 0) continue;
        const bool worse = worst < 0 || count > worst_count ||
                           (count == worst_count && (confirmed[m] < confirmed[worst] ||
                                                     (confirmed[m] == confirmed[worst] && sum > worst_sum)));
        if (worse) worst = m, worst_count = count, worst_sum = sum;
      }
      any = worst >= 0;
      if (any) off[f][worst] = 1;
    }
  }
  return off;
}

}  // namespace mocapsolve
