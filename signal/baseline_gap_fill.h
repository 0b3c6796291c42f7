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
//               in human motion data using marker intercorrelations": the #F x 3#M
//               matrix is modelled as its column means plus a low-rank part spanned by
//               the principal components that explain `pca_variance` of the variance;
//               missing entries start from the linear fill and are replaced by their
//               low-rank reconstruction until they change less than `pca_tolerance`
//               (iterative PCA imputation). Their method weights markers by distance to
//               the missing one and solves once; this variant uses every marker alike and
//               iterates, which needs no complete frames (real takes may have none).
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
