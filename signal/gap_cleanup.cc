#include "signal/gap_cleanup.h"

#include "signal/gap_fill.h"

namespace mocapsolve {

int RemoveSmallTracks(int max_track, MarkerTrajectories* markers) {
  return RemoveSmallTracks(max_track, nullptr, markers);
}

int RemoveSmallTracks(int max_track, const std::function<bool(int, int)>& trusted, MarkerTrajectories* markers) {
  int removed = 0;
  const int n = markers->num_frames();
  for (int m = 0; m < markers->num_markers(); ++m) {
    for (int f = 0; f < n; ++f) {
      if (!markers->valid(f, m)) continue;
      int end = f;
      while (end + 1 < n && markers->valid(end + 1, m)) ++end;
      const bool enclosed = f > 0 && end + 1 < n;  // Missing on both sides.
      bool kept = false;
      for (int g = f; trusted && g <= end && !kept; ++g) kept = trusted(g, m);
      if (enclosed && !kept && end - f + 1 <= max_track) {
        for (int g = f; g <= end; ++g) markers->SetMissing(g, m);
        removed += end - f + 1;
      }
      f = end;
    }
  }
  return removed;
}

int FillSmallGaps(int max_gap, MarkerTrajectories* markers) {
  // The naive polynomial is Algorithm 3's Hermite with a zero reference path.
  MarkerTrajectories zero(markers->labels(), markers->num_frames());
  for (int f = 0; f < markers->num_frames(); ++f) {
    for (int m = 0; m < markers->num_markers(); ++m) zero.SetSample(f, m, Eigen::Vector3d::Zero());
  }
  int filled = 0;
  for (const Gap& gap : FindGaps(*markers)) {
    if (gap.length() > max_gap || gap.first == 0 || gap.last + 1 == markers->num_frames()) continue;
    if (FillGapFromReference(gap, zero, GapFillOptions(), markers).ok()) filled += gap.length();
  }
  return filled;
}

}  // namespace mocapsolve
