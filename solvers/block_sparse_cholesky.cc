#include "solvers/block_sparse_cholesky.h"

#include <algorithm>
#include <set>

#include <Eigen/Cholesky>
#include <glog/logging.h>

namespace mocapsolve {

void BlockSparseCholesky::Analyze(int num_blocks, const std::vector<std::pair<int, int>>& pairs) {
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
    Eigen::LLT<Eigen::Matrix3d> llt(diagonal_[k]);
    if (llt.info() != Eigen::Success) return false;
    diagonal_[k] = llt.matrixL();
    const Eigen::Matrix3d inverse_transpose =
        diagonal_[k].triangularView<Eigen::Lower>().solve(Eigen::Matrix3d::Identity()).transpose();
    std::vector<Eigen::Matrix3d>& column = values_[k];
    for (Eigen::Matrix3d& v : column) v = v * inverse_transpose;  // L_ik = A_ik L_kk^-T.
    const std::vector<int>& rows = rows_[k];
    int index = 0;
    for (size_t a = 0; a < rows.size(); ++a) {
      for (size_t b = 0; b <= a; ++b, ++index) {
        const int target_column = update_column_[k][index];
        const int target_entry = update_entry_[k][index];
        Eigen::Matrix3d& target =
            target_entry < 0 ? diagonal_[target_column] : values_[target_column][target_entry];
        target.noalias() -= column[a] * column[b].transpose();
      }
    }
  }
  return true;
}

void BlockSparseCholesky::Solve(const Eigen::VectorXd& b, Eigen::VectorXd* x) const {
  const int n = num_blocks();
  Eigen::VectorXd y = b;
  for (int k = 0; k < n; ++k) {  // L y = b.
    y.segment<3>(3 * k) = diagonal_[k].triangularView<Eigen::Lower>().solve(y.segment<3>(3 * k));
    const Eigen::Vector3d yk = y.segment<3>(3 * k);
    for (size_t e = 0; e < rows_[k].size(); ++e) y.segment<3>(3 * rows_[k][e]) -= values_[k][e] * yk;
  }
  for (int k = n - 1; k >= 0; --k) {  // L^T x = y.
    Eigen::Vector3d v = y.segment<3>(3 * k);
    for (size_t e = 0; e < rows_[k].size(); ++e) v -= values_[k][e].transpose() * y.segment<3>(3 * rows_[k][e]);
    y.segment<3>(3 * k) = diagonal_[k].transpose().triangularView<Eigen::Upper>().solve(v);
  }
  *x = std::move(y);
}

int BlockSparseCholesky::num_factor_blocks() const {
  int count = 0;
  for (const auto& rows : rows_) count += static_cast<int>(rows.size());
  return count;
}

}  // namespace mocapsolve
