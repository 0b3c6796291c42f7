#include "solvers/block_sparse_cholesky.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <glog/logging.h>

#include "solvers/block_update_3x3.h"

namespace mocapsolve {
namespace {

// target(0:A, 0:B) -= a(0:A, 0:K) b(0:B, 0:K)^T: the update of one block pair.
template <int A, int B, int K>
void Update(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, Eigen::Matrix3d* target) {
  target->topLeftCorner<A, B>().noalias() -= a.topLeftCorner<A, K>() * b.topLeftCorner<B, K>().transpose();
}
// The full block, the common one: written out (block_update_3x3.h), the same bits.
template <>
void Update<3, 3, 3>(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, Eigen::Matrix3d* target) {
  SubtractProductTransposed3(a, b, target);
}
using UpdateKernel = void (*)(const Eigen::Matrix3d&, const Eigen::Matrix3d&, Eigen::Matrix3d*);
#define MOCAPSOLVE_UPDATES(A, B) {Update<A, B, 1>, Update<A, B, 2>, Update<A, B, 3>}
constexpr UpdateKernel kUpdates[3][3][3] = {
    {MOCAPSOLVE_UPDATES(1, 1), MOCAPSOLVE_UPDATES(1, 2), MOCAPSOLVE_UPDATES(1, 3)},
    {MOCAPSOLVE_UPDATES(2, 1), MOCAPSOLVE_UPDATES(2, 2), MOCAPSOLVE_UPDATES(2, 3)},
    {MOCAPSOLVE_UPDATES(3, 1), MOCAPSOLVE_UPDATES(3, 2), MOCAPSOLVE_UPDATES(3, 3)}};
#undef MOCAPSOLVE_UPDATES

// v(0:R, 0:K) <- v(0:R, 0:K) inverse(0:K, 0:K)^T: L_ik = A_ik L_kk^-T.
template <int R, int K>
void Scale(const Eigen::Matrix3d& inverse, Eigen::Matrix3d* v) {
  const Eigen::Matrix<double, R, K> a = v->topLeftCorner<R, K>();
  v->topLeftCorner<R, K>().noalias() = a * inverse.topLeftCorner<K, K>().transpose();
}
using ScaleKernel = void (*)(const Eigen::Matrix3d&, Eigen::Matrix3d*);
constexpr ScaleKernel kScales[3][3] = {{Scale<1, 1>, Scale<1, 2>, Scale<1, 3>},
                                       {Scale<2, 1>, Scale<2, 2>, Scale<2, 3>},
                                       {Scale<3, 1>, Scale<3, 2>, Scale<3, 3>}};

// In place: the lower triangle of a (3 x 3, SPD) becomes L, a = L L^T; *inverse = L^-1.
// False if a pivot is not positive.
bool Cholesky3(Eigen::Matrix3d* a, Eigen::Matrix3d* inverse) {
  Eigen::Matrix3d& m = *a;
  const double l00 = m(0, 0);
  if (!(l00 > 0.0)) return false;
  const double a0 = std::sqrt(l00);
  const double b = m(1, 0) / a0, d = m(2, 0) / a0;
  const double c2 = m(1, 1) - b * b;
  if (!(c2 > 0.0)) return false;
  const double c = std::sqrt(c2);
  const double e = (m(2, 1) - d * b) / c;
  const double f2 = m(2, 2) - d * d - e * e;
  if (!(f2 > 0.0)) return false;
  const double f = std::sqrt(f2);
  m << a0, 0, 0, b, c, 0, d, e, f;
  *inverse << 1.0 / a0, 0, 0, -b / (a0 * c), 1.0 / c, 0, (b * e - c * d) / (a0 * c * f), -e / (c * f), 1.0 / f;
  return true;
}

}  // namespace

void BlockSparseCholesky::Analyze(int num_blocks, const std::vector<std::pair<int, int>>& pairs,
                                  const std::vector<int>& sizes) {
  CHECK(sizes.empty() || static_cast<int>(sizes.size()) == num_blocks);
  sizes_ = sizes.empty() ? std::vector<int>(num_blocks, 3) : sizes;
  for (int s : sizes_) CHECK(s >= 1 && s <= 3);
  std::vector<std::set<int>> structure(num_blocks);
  for (const auto& pair : pairs) {
    CHECK(pair.first > pair.second && pair.second >= 0 && pair.first < num_blocks);
    structure[pair.second].insert(pair.first);
  }
  // Symbolic factorization: column k's fill joins its elimination-tree parent's column.
  for (int k = 0; k < num_blocks; ++k) {
    if (structure[k].empty()) continue;
    const int parent = *structure[k].begin();
    for (int row : structure[k]) {
      if (row != parent) structure[parent].insert(row);
    }
  }
  rows_.assign(num_blocks, {});
  values_.assign(num_blocks, {});
  diagonal_.assign(num_blocks, Eigen::Matrix3d::Zero());
  inverse_.assign(num_blocks, Eigen::Matrix3d::Zero());
  for (int k = 0; k < num_blocks; ++k) {
    rows_[k].assign(structure[k].begin(), structure[k].end());
    values_[k].assign(rows_[k].size(), Eigen::Matrix3d::Zero());
  }
  auto entry = [this](int column, int row) {
    const auto it = std::lower_bound(rows_[column].begin(), rows_[column].end(), row);
    CHECK(it != rows_[column].end() && *it == row);
    return static_cast<int>(it - rows_[column].begin());
  };
  column_of_slot_.clear();
  entry_of_slot_.clear();
  for (const auto& pair : pairs) {
    column_of_slot_.push_back(pair.second);
    entry_of_slot_.push_back(entry(pair.second, pair.first));
  }
  update_column_.assign(num_blocks, {});
  update_entry_.assign(num_blocks, {});
  for (int k = 0; k < num_blocks; ++k) {
    const std::vector<int>& rows = rows_[k];
    for (size_t a = 0; a < rows.size(); ++a) {
      for (size_t b = 0; b <= a; ++b) {
        update_column_[k].push_back(rows[b]);
        update_entry_[k].push_back(a == b ? -1 : entry(rows[b], rows[a]));
      }
    }
  }
}

void BlockSparseCholesky::SetZero() {
  for (Eigen::Matrix3d& d : diagonal_) d.setZero();
  for (auto& column : values_) {
    for (Eigen::Matrix3d& v : column) v.setZero();
  }
}

bool BlockSparseCholesky::Factorize() {
  const int n = num_blocks();
  for (int k = 0; k < n; ++k) {
    if (!Cholesky3(&diagonal_[k], &inverse_[k])) return false;
    const int sk = sizes_[k] - 1;
    std::vector<Eigen::Matrix3d>& column = values_[k];
    const std::vector<int>& rows = rows_[k];
    for (size_t e = 0; e < rows.size(); ++e) kScales[sizes_[rows[e]] - 1][sk](inverse_[k], &column[e]);
    int index = 0;
    for (size_t a = 0; a < rows.size(); ++a) {
      const int sa = sizes_[rows[a]] - 1;
      for (size_t b = 0; b <= a; ++b, ++index) {
        const int target_column = update_column_[k][index];
        const int target_entry = update_entry_[k][index];
        Eigen::Matrix3d& target =
            target_entry < 0 ? diagonal_[target_column] : values_[target_column][target_entry];
        kUpdates[sa][sizes_[rows[b]] - 1][sk](column[a], column[b], &target);
      }
    }
  }
  return true;
}

void BlockSparseCholesky::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  const int n = num_blocks();
  if (x != &b) *x = b;  // Sized once by a caller that reuses x: no allocation.
  Eigen::VectorXd& y = *x;
  for (int k = 0; k < n; ++k) {  // L y = b.
    const Eigen::Vector3d yk = inverse_[k] * y.segment<3>(3 * k);
    y.segment<3>(3 * k) = yk;
    for (size_t e = 0; e < rows_[k].size(); ++e) y.segment<3>(3 * rows_[k][e]).noalias() -= values_[k][e] * yk;
  }
  for (int k = n - 1; k >= 0; --k) {  // L^T x = y.
    Eigen::Vector3d v = y.segment<3>(3 * k);
    for (size_t e = 0; e < rows_[k].size(); ++e) v.noalias() -= values_[k][e].transpose() * y.segment<3>(3 * rows_[k][e]);
    y.segment<3>(3 * k) = inverse_[k].transpose() * v;
  }
}

int BlockSparseCholesky::num_factor_blocks() const {
  int count = 0;
  for (const auto& rows : rows_) count += static_cast<int>(rows.size());
  return count;
}

}  // namespace mocapsolve
