#include "signal/rough_run_extension.h"

#include <algorithm>
#include <vector>

#include <glog/logging.h>

namespace mocapsolve {

double SecondDifference(const MarkerTrajectories& samples, const MarkerTrajectories* reference, int marker,
                        int frame) {
  if (frame < 1 || frame + 1 >= samples.num_frames()) return -1.0;
  for (int f = frame - 1; f <= frame + 1; ++f) {
    if (!samples.valid(f, marker) || (reference != nullptr && !reference->valid(f, marker))) return -1.0;
  }
  auto r = [&](int f) -> Eigen::Vector3d {
    return reference != nullptr ? Eigen::Vector3d(samples.position(f, marker) - reference->position(f, marker))
                                : Eigen::Vector3d(samples.position(f, marker));
  };
  return (r(frame + 1) - 2.0 * r(frame) + r(frame - 1)).norm();
}

double MedianSecondDifference(const MarkerTrajectories& samples, const MarkerTrajectories* reference, int marker,
                              int first, int last) {
  std::vector<double> values;
  for (int f = std::max(1, first); f <= std::min(samples.num_frames() - 2, last); ++f) {
    const double s = SecondDifference(samples, reference, marker, f);
    if (s >= 0.0) values.push_back(s);
  }
  if (values.empty()) return -1.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

int ExtendRoughRun(const Gap& gap, const MarkerTrajectories& samples, const MarkerTrajectories& reference,
                   double threshold, int max_extent, MarkerTrajectories* x, MarkerTrajectories* also) {
  CHECK_EQ(samples.num_frames(), x->num_frames());
  CHECK_EQ(reference.num_frames(), x->num_frames());
  CHECK(gap.first >= 0 && gap.last < x->num_frames() && gap.first <= gap.last);
  const int m = gap.marker;
  auto rough = [&](int f) { return SecondDifference(samples, &reference, m, f) > threshold; };
  int cut = 0;
  auto cut_sample = [&](int f) {
    if (!x->valid(f, m)) return;
    x->SetMissing(f, m);
    if (also != nullptr) also->SetMissing(f, m);
    ++cut;
  };
  // Left: the stretch's first frame a (s(a) > threshold, s(a - 1) not); its interior
  // starts at a + 1.
  int a = gap.first;
  while (a - 1 >= 0 && gap.first - (a - 1) <= max_extent + 1 && rough(a - 1)) --a;
  for (int f = a + 1; f < gap.first; ++f) cut_sample(f);
  int b = gap.last;
  while (b + 1 < x->num_frames() && (b + 1) - gap.last <= max_extent + 1 && rough(b + 1)) ++b;
  for (int f = gap.last + 1; f < b; ++f) cut_sample(f);
  return cut;
}

}  // namespace mocapsolve
