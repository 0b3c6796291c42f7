// The 5-tap generating kernel of the Gaussian pyramid (Burt & Adelson 1983; Huang,
// Boulic & Thalmann, "Motion editing using multiresolution filtering", eq. 1).
//
// REDUCE: G_{l+1}(i) = sum_{m=-2..2} w(m) G_l(2i + m), with the kernel
//   w(0) = a, w(+-1) = b, w(+-2) = c,
// constrained to be symmetric, normalized (a + 2b + 2c = 1) and to give every level-l
// node the same total weight into level l+1 (equal contribution: a + 2c = 2b). With a
// free, this fixes b = 1/4 and c = 1/4 - a/2. a = 0.4 (the default) is the paper's and
// Burt & Adelson's Gaussian-like choice; a = 3/8 is the cubic B-spline.
#ifndef MOCAPSOLVE_SIGNAL_GENERATING_KERNEL_H_
#define MOCAPSOLVE_SIGNAL_GENERATING_KERNEL_H_

#include <array>

#include "kinematics/status.h"

namespace mocapsolve {

struct GeneratingKernel {
  double a = 0.4;  // The free centre weight.

  double b() const { return 0.25; }
  double c() const { return 0.25 - 0.5 * a; }
  // w(-2), w(-1), w(0), w(1), w(2).
  std::array<double, 5> weights() const { return {c(), b(), a, b(), c()}; }

  // a in [0.25, 0.75]: outside, c leaves [-1/8, 1/8] and the filter is no longer
  // low-pass (a = 0.25 is a box-like kernel; a > 0.5 gives negative side lobes).
  Status Validate() const {
    if (!(a >= 0.25 && a <= 0.75)) {
      return Status::Error("kernel a must be in [0.25, 0.75] (paper: 0.4)");
    }
    return Status::Ok();
  }
};

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_GENERATING_KERNEL_H_
