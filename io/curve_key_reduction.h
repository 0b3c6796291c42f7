// Linear key reduction of a sampled animation curve, for formats that store a time with
// every key (FBX: each AnimationCurve holds its own KeyTime array).
//
// Of samples v_0 .. v_{n-1} at frames 0 .. n-1, finds keys (k_0 = 0 < k_1 < ... < k_m =
// n - 1, values y_0 = v_0, y_1, ..., y_m) whose linear interpolation reproduces every sample
// within the tolerance:
//     | v_i - (y_a + (y_b - y_a) (i - k_a) / (k_b - k_a)) | <= tolerance,   k_a <= i <= k_b.
// A key's value may differ from its sample by up to the tolerance (free knots: the line may
// run anywhere in the band, which takes fewer keys than lines through samples). Greedy: from
// a key (k_a, y_a) each later sample i bounds the slope to [(v_i - tol - y_a) / (i - k_a),
// (v_i + tol - y_a) / (i - k_a)]; the segment extends while the intersection of those
// intervals is not empty, and the next key takes the middle of the last non-empty one. O(n).
// Tolerance 0 keeps the samples' own values and drops only samples the line through the
// neighbouring keys reproduces exactly (a constant curve keeps its two ends). Values are
// stored as float, so a kept value may add float rounding (~1e-7 relative) to the bound.
#ifndef MOCAPSOLVE_IO_CURVE_KEY_REDUCTION_H_
#define MOCAPSOLVE_IO_CURVE_KEY_REDUCTION_H_

#include <vector>

namespace mocapsolve {

struct CurveKeys {
  std::vector<int> frames;    // Increasing; the first and the last sample's always.
  std::vector<float> values;  // One per frame.
};

// {} for no samples, one key for one.
CurveKeys ReduceLinearKeys(const std::vector<float>& samples, double tolerance);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_CURVE_KEY_REDUCTION_H_
