// Medians of a signal over windows that slide forward: for each knot f_i (ascending), the
// median of x(g) over the valid frames g in [f_i - half, f_i + half] (clipped to the
// signal), taken as Median does elsewhere: the element of rank floor(n / 2) of the n
// values (the upper one of the two middle ones for even n), `fallback` for an empty window.
//
// The values of the current window are kept sorted; moving to the next knot erases the
// frames that leave and inserts those that enter (binary search, then a shift of the
// vector), so a knot costs O(stride * window) element moves instead of a selection over the
// whole window. Ranks do not depend on the order of equal values, so the result is the
// selection's. Non-finite valid values have no order: then every window is selected
// afresh (std::nth_element), as before this was written.
#ifndef MOCAPSOLVE_SIGNAL_WINDOW_MEDIANS_H_
#define MOCAPSOLVE_SIGNAL_WINDOW_MEDIANS_H_

#include <vector>

namespace mocapsolve {

// values and valid: one per frame (same size); knots ascending, inside the signal; half >= 0.
std::vector<double> WindowMedians(const std::vector<double>& values, const std::vector<char>& valid,
                                  const std::vector<int>& knots, int half, double fallback);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_WINDOW_MEDIANS_H_
