#include "problems/marker_repair/swap_detection.h"

#include <algorithm>

namespace mocapsolve {

std::vector<MarkerSwap> UndoSwaps(const MarkerResidualModel& model, const SwapDetectionOptions& options,
                                  MarkerTrajectories* x) {
  const int nf = x->num_frames(), nm = x->num_markers();
  // claim[f][m]: the label sample x_fm is claimed by, or -1.
  std::vector<std::vector<int>> claim(nf, std::vector<int>(nm, -1));
  std::vector<double> own(nm), best(nm);
  for (int f = 0; f < nf; ++f) {
    const auto& p = model.typical_predicted[f];
    for (int m = 0; m < nm; ++m) {
      own[m] = x->valid(f, m) ? (x->position(f, m) - p[m]).norm() : -1.0;
    }
    // Claims on each label: the nearest (relative to the label's gate) wins.
    std::vector<int> winner(nm, -1);
    for (int m = 0; m < nm; ++m) {
      if (own[m] < 0.0 || own[m] <= model.typical_gate[m]) continue;
      const Eigen::Vector3d sample = x->position(f, m);
      int chosen = -1;
      double chosen_ratio = 1.0;
      for (int n = 0; n < nm; ++n) {
        if (n == m || (p[n] - p[m]).norm() > options.radius) continue;
        if (own[n] >= 0.0 && own[n] <= model.typical_gate[n]) continue;  // n is tracked well: not a swap.
        const double d = (sample - p[n]).norm();
        if (d > options.margin * own[m]) continue;
        const double ratio = d / model.typical_gate[n];
        if (ratio <= chosen_ratio) chosen_ratio = ratio, chosen = n;
      }
      if (chosen < 0) continue;
      best[m] = chosen_ratio;
      if (winner[chosen] < 0 || best[winner[chosen]] > chosen_ratio) winner[chosen] = m;
    }
    for (int n = 0; n < nm; ++n) {
      if (winner[n] >= 0) claim[f][winner[n]] = n;
    }
  }
  // Persistence: drop claims in runs shorter than min_frames.
  for (int m = 0; m < nm; ++m) {
    for (int f = 0; f < nf;) {
      const int n = claim[f][m];
      int g = f + 1;
      while (g < nf && claim[g][m] == n) ++g;
      if (n >= 0 && g - f < options.min_frames) {
        for (int k = f; k < g; ++k) claim[k][m] = -1;
      }
      f = g;
    }
  }
  // Relabel, and gather the intervals (consecutive frames with the same exchanges).
  std::vector<MarkerSwap> swaps;
  std::vector<std::pair<int, int>> previous;
  int samples = 0;
  auto close = [&] {
    if (!swaps.empty() && samples > 0) {
      swaps.back().distance_before /= samples;
      swaps.back().distance_after /= samples;
    }
    samples = 0;
  };
  for (int f = 0; f < nf; ++f) {
    std::vector<std::pair<int, int>> pairs;
    for (int m = 0; m < nm; ++m) {
      if (claim[f][m] >= 0) pairs.emplace_back(m, claim[f][m]);
    }
    if (pairs.empty()) {
      if (!previous.empty()) close();
      previous.clear();
      continue;
    }
    if (pairs != previous) {
      close();
      swaps.push_back({f, f, pairs, 0.0, 0.0});
    }
    MarkerSwap& swap = swaps.back();
    swap.last = f;
    std::vector<Eigen::Vector3d> samples_now(nm);
    std::vector<char> gave(nm, 0), got(nm, 0);
    for (const auto& [from, to] : pairs) {
      samples_now[from] = x->position(f, from);
      swap.distance_before += (samples_now[from] - model.typical_predicted[f][from]).norm();
      swap.distance_after += (samples_now[from] - model.typical_predicted[f][to]).norm();
      ++samples;
      gave[from] = 1;
    }
    for (const auto& [from, to] : pairs) {
      x->SetSample(f, to, samples_now[from]);
      got[to] = 1;
    }
    for (int m = 0; m < nm; ++m) {
      if (gave[m] && !got[m]) x->SetMissing(f, m);
    }
    previous = pairs;
  }
  close();
  return swaps;
}

}  // namespace mocapsolve
