#include "problems/marker_repair/swap_detection.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mocapsolve {

namespace {

using Claims = std::vector<std::vector<int>>;

// The sample label n has at frame f after relabelling by `claim` (NaN if none).
Eigen::Vector3d Relabelled(const MarkerTrajectories& x, const Claims& claim, int f, int n) {
  const int nm = x.num_markers();
  for (int m = 0; m < nm; ++m) {
    if (claim[f][m] == n) return x.position(f, m);
  }
  if (claim[f][n] >= 0) return Eigen::Vector3d::Constant(NAN);
  return x.position(f, n);
}

// Frames a label's continuation reaches back over where it has no (relabelled) sample, in
// the pass into gaps: a label whose samples a gap hides while the swap goes on is continued
// from before the gap.
constexpr int kContinuityReach = 15;

// Where label n is expected at frame f from its last two (relabelled) samples before f, in
// the direction of step, the last within `reach` frames: extrapolated at constant velocity,
// or the last sample; NaN if unknown.
Eigen::Vector3d Continued(const MarkerTrajectories& x, const Claims& claim, int f, int step, int n, int reach = 1) {
  auto inside = [&](int k) { return k >= 0 && k < x.num_frames(); };
  int g = f - step;
  Eigen::Vector3d a = Eigen::Vector3d::Constant(NAN);
  for (; inside(g) && std::abs(f - g) <= reach; g -= step) {
    a = Relabelled(x, claim, g, n);
    if (a.allFinite()) break;
  }
  if (!a.allFinite()) return a;
  const int h = g - step;
  if (!inside(h)) return a;
  const Eigen::Vector3d b = Relabelled(x, claim, h, n);
  return b.allFinite() ? Eigen::Vector3d(a + (a - b) * std::abs(f - g)) : a;
}

// The exchange `pairs` (claims at frame f - step) carried on to frame f if, by continuity,
// it costs less than margin times the identity (see ExtendByContinuity).
void ExtendExchange(const SwapDetectionOptions& options, const MarkerResidualModel& model,
                    const MarkerTrajectories& x, int f, int step, const std::vector<std::pair<int, int>>& pairs,
                    bool only_into_gaps, Claims* claim) {
  const int nm = x.num_markers();
  // Only where none of the labels involved has a claim of its own at f...
  std::vector<int> labels;
  for (const auto& [from, to] : pairs) labels.push_back(from), labels.push_back(to);
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  // ...or whose claims at f are part of the exchange at g (completed here).
  bool free = true;
  for (const int l : labels) {
    const int to = (*claim)[f][l];
    if (to >= 0) free &= std::find(pairs.begin(), pairs.end(), std::make_pair(l, to)) != pairs.end();
    for (int m = 0; m < nm; ++m) {
      if ((*claim)[f][m] == l) free &= std::find(pairs.begin(), pairs.end(), std::make_pair(m, l)) != pairs.end();
    }
  }
  if (!free) return;
  const int reach = only_into_gaps ? kContinuityReach : 1;
  if (only_into_gaps) {
    bool gap = false;
    for (const int l : labels) gap |= !x.valid(f, l);
    if (!gap) return;
  }
  bool same = true;
  for (const auto& [from, to] : pairs) same &= (*claim)[f][from] == to;
  if (same) return;
  double identity = 0.0, swapped = 0.0, gate = std::numeric_limits<double>::infinity();
  bool known = true;
  for (const int l : labels) {
    if (!x.valid(f, l)) continue;
    const Eigen::Vector3d expected = Continued(x, *claim, f, step, l, reach);
    known &= expected.allFinite();
    if (known) identity += (x.position(f, l) - expected).norm();
    gate = std::min(gate, model.typical_gate[l]);
  }
  int samples = 0;
  for (const auto& [from, to] : pairs) {
    if (!x.valid(f, from)) continue;
    const Eigen::Vector3d expected = Continued(x, *claim, f, step, to, reach);
    known &= expected.allFinite();
    if (known) swapped += (x.position(f, from) - expected).norm();
    ++samples;
  }
  if (!known || samples == 0 || identity <= gate || swapped > options.margin * identity) return;
  if (only_into_gaps) {
    // Continuity across a gap is a long extrapolation, and two nearby markers may lie
    // closer than its error: the kinematic fit decides too, the exchange fitting the
    // typical predictions no worse than the identity.
    double fit_identity = 0.0, fit_swapped = 0.0;
    for (const auto& [from, to] : pairs) {
      if (!x.valid(f, from)) continue;
      fit_identity += (x.position(f, from) - model.typical_predicted[f][from]).norm();
      fit_swapped += (x.position(f, from) - model.typical_predicted[f][to]).norm();
    }
    if (fit_swapped > fit_identity) return;
  }
  for (const auto& [from, to] : pairs) (*claim)[f][from] = to;
}

// The exchanges of frame f - step's claims, grouped into cycles of labels (a -> b -> a).
std::vector<std::vector<std::pair<int, int>>> ExchangeCycles(const std::vector<std::pair<int, int>>& pairs) {
  std::vector<std::vector<std::pair<int, int>>> cycles;
  std::vector<char> used(pairs.size(), 0);
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (used[i]) continue;
    std::vector<int> labels = {pairs[i].first, pairs[i].second};
    cycles.emplace_back();
    for (bool grew = true; grew;) {
      grew = false;
      for (size_t k = 0; k < pairs.size(); ++k) {
        if (used[k]) continue;
        const bool joins = std::count(labels.begin(), labels.end(), pairs[k].first) ||
                           std::count(labels.begin(), labels.end(), pairs[k].second);
        if (!joins) continue;
        used[k] = 1, grew = true;
        cycles.back().push_back(pairs[k]);
        labels.push_back(pairs[k].first), labels.push_back(pairs[k].second);
      }
    }
  }
  return cycles;
}

// Claims carried frame by frame in the direction of step. With only_into_gaps, only into
// frames where one of the exchanged labels has no sample, each cycle of labels judged on
// its own (at a frame where several swaps go on, the others' gain would carry a swap that
// ended), the continuation reaching across up to kContinuityReach frames.
void ExtendByContinuity(const SwapDetectionOptions& options, const MarkerResidualModel& model,
                        const MarkerTrajectories& x, int step, Claims* claim, bool only_into_gaps = false) {
  const int nf = x.num_frames(), nm = x.num_markers();
  const int begin = step > 0 ? 1 : nf - 2, end = step > 0 ? nf : -1;
  for (int f = begin; f != end; f += step) {
    const int g = f - step;
    std::vector<std::pair<int, int>> pairs;
    for (int m = 0; m < nm; ++m) {
      if ((*claim)[g][m] >= 0) pairs.emplace_back(m, (*claim)[g][m]);
    }
    if (pairs.empty()) continue;
    if (!only_into_gaps) {
      ExtendExchange(options, model, x, f, step, pairs, false, claim);
      continue;
    }
    for (const auto& cycle : ExchangeCycles(pairs)) ExtendExchange(options, model, x, f, step, cycle, true, claim);
  }
}

// Where label l is expected at frame f from frames f - step and f - 2 step of the samples
// as captured (constant velocity, or the last sample; NaN if f - step is unknown).
Eigen::Vector3d Extrapolated(const MarkerTrajectories& x, int f, int step, int l) {
  const int g = f - step, h = f - 2 * step;
  if (g < 0 || g >= x.num_frames() || !x.valid(g, l)) return Eigen::Vector3d::Constant(NAN);
  if (h < 0 || h >= x.num_frames() || !x.valid(h, l)) return x.position(g, l);
  return 2.0 * x.position(g, l) - x.position(h, l);
}

// Whether labels a and b exchange trajectories between frames f - 1 and f: seen from
// either side (extrapolated forward to f, backward to f - 1), the exchanged labelling
// continues the other side within event_margin of the identity's cost, and the identity
// jumps by more than the two labels' gates together.
bool ExchangeEvent(const MarkerResidualModel& model, const SwapDetectionOptions& options,
                   const MarkerTrajectories& x, int f, int a, int b) {
  const double jump = model.typical_gate[a] + model.typical_gate[b];
  for (const int step : {+1, -1}) {
    const int at = step > 0 ? f : f - 1;
    const Eigen::Vector3d ea = Extrapolated(x, at, step, a), eb = Extrapolated(x, at, step, b);
    if (!ea.allFinite() || !eb.allFinite()) return false;
    const Eigen::Vector3d xa = x.position(at, a), xb = x.position(at, b);
    const double identity = (xa - ea).norm() + (xb - eb).norm();
    const double exchanged = (xa - eb).norm() + (xb - ea).norm();
    if (identity <= jump || exchanged > options.event_margin * identity) return false;
  }
  return true;
}

// Exchange events decide the pair's labelling where the reference cannot (a swap from
// the take's first frame, which the reference follows from its start; a bone that one
// marker pins, which the reference turns to follow the swap). Over each run of frames
// where both labels are observed, the events cut the run into segments whose labellings
// alternate; of the two alternations, the one whose exchanged segments fit the typical
// predictions better (summed over the segments: identity cost less exchanged cost) is
// kept, so a segment the reference followed is outweighed by the segments it did not.
// The pair's claims in such a run are replaced by that labelling.
void DecideByExchangeEvents(const MarkerResidualModel& model, const SwapDetectionOptions& options,
                            const MarkerTrajectories& x, Claims* claim) {
  const int nf = x.num_frames(), nm = x.num_markers();
  for (int a = 0; a < nm; ++a) {
    for (int b = a + 1; b < nm; ++b) {
      for (int first = 0; first < nf;) {
        if (!x.valid(first, a) || !x.valid(first, b)) {
          ++first;
          continue;
        }
        int last = first;
        while (last + 1 < nf && x.valid(last + 1, a) && x.valid(last + 1, b)) ++last;
        // Frames [first, last], both observed; events at frames first + 1 .. last.
        std::vector<int> events;
        for (int f = first + 1; f <= last; ++f) {
          if ((x.position(f, a) - x.position(f, b)).norm() > options.radius) continue;
          if (ExchangeEvent(model, options, x, f, a, b)) events.push_back(f);
        }
        const int run_first = first;
        first = last + 1;
        if (events.empty()) continue;
        // d[s]: identity cost less exchanged cost over segment s.
        std::vector<int> bounds = {run_first};
        bounds.insert(bounds.end(), events.begin(), events.end());
        bounds.push_back(last + 1);
        const auto& t = model.typical_predicted;
        double sum[2] = {0.0, 0.0};
        for (size_t s = 0; s + 1 < bounds.size(); ++s) {
          for (int f = bounds[s]; f < bounds[s + 1]; ++f) {
            const Eigen::Vector3d xa = x.position(f, a), xb = x.position(f, b);
            sum[s % 2] += (xa - t[f][a]).norm() + (xb - t[f][b]).norm() - (xa - t[f][b]).norm() -
                          (xb - t[f][a]).norm();
          }
        }
        const size_t parity = sum[1] > sum[0] ? 1 : 0;
        // Inside an exchanged segment both trajectories must be smooth: a label that jumps
        // there too (an exchange with a third label, as when two swaps overlap) makes a
        // chain the pair's events do not describe, left to the claims.
        bool smooth = true;
        for (size_t s = parity; s + 1 < bounds.size() && smooth; s += 2) {
          for (int f = bounds[s] + 2; f < bounds[s + 1] && smooth; ++f) {
            for (const int l : {a, b}) {
              const Eigen::Vector3d bend = x.position(f, l) - 2.0 * x.position(f - 1, l) + x.position(f - 2, l);
              smooth &= bend.norm() <= model.typical_gate[l];
            }
          }
        }
        if (!smooth) continue;
        for (size_t s = 0; s + 1 < bounds.size(); ++s) {
          for (int f = bounds[s]; f < bounds[s + 1]; ++f) {
            auto& c = (*claim)[f];
            if (s % 2 == parity) {
              for (int m = 0; m < nm; ++m) {
                if (c[m] == a || c[m] == b) c[m] = -1;
              }
              c[a] = b, c[b] = a;
            } else {
              if (c[a] == b) c[a] = -1;
              if (c[b] == a) c[b] = -1;
            }
          }
        }
      }
    }
  }
}

}  // namespace

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
    // Exchanges completed: when m's sample goes to n and n's outlying sample is closer to
    // m's prediction than to its own, and nobody else claims m, n's sample goes to m (the
    // reference, partly drawn toward the swapped labels, may leave it outside m's gate).
    for (int n = 0; n < nm; ++n) {
      const int m = winner[n];
      if (m < 0 || winner[m] >= 0 || claim[f][n] >= 0 || own[n] < 0.0 || own[n] <= model.typical_gate[n]) continue;
      if ((x->position(f, n) - p[m]).norm() < options.margin * own[n]) claim[f][n] = m, winner[m] = n;
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
  // Continuity: the reference drifts toward the swapped labels after a swap began (a
  // robust solve still partly follows two wrong markers of a bone), so the claims seen at
  // a swap's onset are carried forward, and those seen at its end backward, while the
  // exchange keeps the relabelled trajectories more continuous than the identity.
  ExtendByContinuity(options, model, *x, +1, &claim);
  ExtendByContinuity(options, model, *x, -1, &claim);
  DecideByExchangeEvents(model, options, *x, &claim);
  // The exchanges the events decided carried on into the frames beside them where one of
  // the labels is missing (a swap that begins or ends inside a gap shows no event there),
  // by the same continuity test.
  ExtendByContinuity(options, model, *x, +1, &claim, true);
  ExtendByContinuity(options, model, *x, -1, &claim, true);
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
