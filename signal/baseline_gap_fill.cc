#include "signal/baseline_gap_fill.h"

#include <algorithm>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

#include "signal/gap_cleanup.h"
#include "signal/gap_fill.h"

namespace mocapsolve {
namespace {

// Holds the nearest valid sample over gaps at the start or the end; returns the count.
int HoldEnds(MarkerTrajectories* markers) {
  int filled = 0;
  const int n = markers->num_frames();
  for (const Gap& gap : FindGaps(*markers)) {
    if (gap.first > 0 && gap.last + 1 < n) continue;
    if (gap.first == 0 && gap.last + 1 == n) continue;  // Missing all take.
    const Eigen::Vector3d held = markers->position(gap.first == 0 ? gap.last + 1 : gap.first - 1, gap.marker);
    for (int f = gap.first; f <= gap.last; ++f) markers->SetSample(f, gap.marker, held);
    filled += gap.length();
  }
  return filled;
}

}  // namespace

int FillGapsLinear(MarkerTrajectories* markers) {
  int filled = 0;
  for (const Gap& gap : FindGaps(*markers)) {
    if (gap.first == 0 || gap.last + 1 == markers->num_frames()) continue;
    const Eigen::Vector3d a = markers->position(gap.first - 1, gap.marker);
    const Eigen::Vector3d b = markers->position(gap.last + 1, gap.marker);
    const double span = gap.length() + 1;
    for (int f = gap.first; f <= gap.last; ++f) {
      markers->SetSample(f, gap.marker, a + (b - a) * ((f - gap.first + 1) / span));
    }
    filled += gap.length();
  }
  return filled + HoldEnds(markers);
}

int FillGapsPolynomial(MarkerTrajectories* markers) {
  const int filled = FillSmallGaps(std::numeric_limits<int>::max(), markers);
  return filled + HoldEnds(markers);
}

namespace {

// Principal directions of the rows of `data` (about `mean`) that explain `variance` of it.
Eigen::MatrixXd PrincipalBasis(const Eigen::MatrixXd& centred, double variance) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(centred.transpose() * centred);
  const Eigen::VectorXd& values = eigen.eigenvalues();  // Ascending.
  const int columns = static_cast<int>(values.size());
  const double total = std::max(values.sum(), std::numeric_limits<double>::min());
  int keep = 0;
  double explained = 0.0;
  while (keep < columns && explained < variance * total) explained += values(columns - 1 - keep++);
  keep = std::min(std::max(keep, 1), std::max<int>(1, static_cast<int>(centred.rows()) - 1));
  return eigen.eigenvectors().rightCols(keep);
}

}  // namespace

int FillGapsPca(const PcaFillOptions& options, MarkerTrajectories* markers) {
  const int n = markers->num_frames(), columns = 3 * markers->num_markers();
  std::vector<std::pair<int, int>> unknown;  // (frame, marker) of samples to fill.
  std::vector<bool> usable(markers->num_markers(), false), complete(n, true);
  for (int m = 0; m < markers->num_markers(); ++m) {
    for (int f = 0; f < n; ++f) usable[m] = usable[m] || markers->valid(f, m);
  }
  for (int f = 0; f < n; ++f) {
    for (int m = 0; m < markers->num_markers(); ++m) {
      if (!markers->valid(f, m) && usable[m]) unknown.push_back({f, m}), complete[f] = false;
    }
  }
  if (unknown.empty() || n < 2) return 0;
  const MarkerTrajectories original = *markers;
  FillGapsLinear(markers);
  // Markers missing all take take no part (their columns stay zero).
  Eigen::MatrixXd data = Eigen::MatrixXd::Zero(n, columns);
  for (int f = 0; f < n; ++f) {
    for (int m = 0; m < markers->num_markers(); ++m) {
      if (usable[m]) data.block<1, 3>(f, 3 * m) = markers->position(f, m).transpose();
    }
  }
  std::vector<int> complete_frames;
  for (int f = 0; f < n; ++f) {
    if (complete[f]) complete_frames.push_back(f);
  }
  if (static_cast<int>(complete_frames.size()) >= std::max(10, columns / 3)) {
    // Gloersen & Federolf: components from the complete frames, then each incomplete
    // frame's coefficients from its known coordinates (least squares).
    Eigen::MatrixXd rows(complete_frames.size(), columns);
    for (size_t i = 0; i < complete_frames.size(); ++i) rows.row(i) = data.row(complete_frames[i]);
    const Eigen::RowVectorXd mean = rows.colwise().mean();
    const Eigen::MatrixXd basis = PrincipalBasis(rows.rowwise() - mean, options.pca_variance);
    for (int f = 0; f < n; ++f) {
      if (complete[f]) continue;
      std::vector<int> known;
      for (int m = 0; m < markers->num_markers(); ++m) {
        if (usable[m] && original.valid(f, m)) known.insert(known.end(), {3 * m, 3 * m + 1, 3 * m + 2});
      }
      Eigen::VectorXd coefficients = Eigen::VectorXd::Zero(basis.cols());
      if (!known.empty()) {
        Eigen::MatrixXd a(known.size(), basis.cols());
        Eigen::VectorXd b(known.size());
        for (size_t i = 0; i < known.size(); ++i) {
          a.row(i) = basis.row(known[i]);
          b(i) = data(f, known[i]) - mean(known[i]);
        }
        coefficients = a.completeOrthogonalDecomposition().solve(b);
      }
      const Eigen::RowVectorXd model = mean + (basis * coefficients).transpose();
      for (int m = 0; m < markers->num_markers(); ++m) {
        if (usable[m] && !original.valid(f, m)) data.block<1, 3>(f, 3 * m) = model.segment<3>(3 * m);
      }
    }
  } else {
    // Too few complete frames: iterative PCA imputation from the linear start.
    for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
      const Eigen::RowVectorXd mean = data.colwise().mean();
      const Eigen::MatrixXd centred = data.rowwise() - mean;
      const Eigen::MatrixXd basis = PrincipalBasis(centred, options.pca_variance);
      const Eigen::MatrixXd model = (centred * basis) * basis.transpose();
      double change = 0.0;
      for (const auto& [f, m] : unknown) {
        for (int k = 0; k < 3; ++k) {
          const double value = mean(3 * m + k) + model(f, 3 * m + k);
          change = std::max(change, std::abs(value - data(f, 3 * m + k)));
          data(f, 3 * m + k) = value;
        }
      }
      if (change < options.pca_tolerance) break;
    }
  }
  for (const auto& [f, m] : unknown) {
    markers->SetSample(f, m, data.block<1, 3>(f, 3 * m).transpose());
  }
  return static_cast<int>(unknown.size());
}

}  // namespace mocapsolve
