// The gap fills marker repair is compared with (issue 4's evaluation, the thesis'
// Table 1). Each fills every missing sample of every marker that has at least one valid
// sample; a marker missing all take stays missing. None of them detects bad samples: they
// fill what is missing and trust the rest.
//
//   linear      straight line between the two edge samples of a gap;
//   polynomial  the "naive polynomial": the cubic Hermite through the edge samples with
//               one-sided difference velocities (gap_cleanup.h's FillSmallGaps at any
//               length);
//   PCA         after Gloersen & Federolf (2016), "Predicting missing marker trajectories
//               in human motion data using marker intercorrelations": the principal
//               components that explain `pca_variance` of the complete frames (every
//               marker present), then each incomplete frame's component coefficients by
//               least squares from its known coordinates, and the missing ones from them.
//               Their method also weights markers by distance to the missing one; this
//               one weights all alike. With too few complete frames (a real take may
//               have none): iterative PCA imputation from the linear fill until the
//               filled entries change less than `pca_tolerance`.
// Gaps that touch the start or the end of the take hold the nearest valid sample in
// linear and polynomial (there is nothing to interpolate toward).
#ifndef MOCAPSOLVE_SIGNAL_BASELINE_GAP_FILL_H_
#define MOCAPSOLVE_SIGNAL_BASELINE_GAP_FILL_H_

#include "kinematics/marker_trajectories.h"

namespace mocapsolve {

// Each returns the number of samples filled.
int FillGapsLinear(MarkerTrajectories* markers);
int FillGapsPolynomial(MarkerTrajectories* markers);

struct PcaFillOptions {
  double pca_variance = 0.99;   // Share of variance the kept components explain.
  int max_iterations = 100;
  double pca_tolerance = 1e-6;  // Largest change of a filled entry, in marker units.
};
int FillGapsPca(const PcaFillOptions& options, MarkerTrajectories* markers);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_BASELINE_GAP_FILL_H_
