// The written-out 3 x 3 block update gives the bits of the Eigen expression it replaces, on
// entries of every magnitude and sign (where the order of the sums shows).
#include "solvers/block_update_3x3.h"

#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

TEST(BlockUpdate3x3, TheBitsOfTheEigenExpression) {
  std::mt19937_64 generator(5);
  std::normal_distribution<double> normal;
  auto entry = [&]() { return normal(generator) * std::exp(3.0 * normal(generator)); };
  int differing = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    Eigen::Matrix3d a, b, t;
    for (int i = 0; i < 9; ++i) a.data()[i] = entry(), b.data()[i] = entry(), t.data()[i] = entry();
    Eigen::Matrix3d expected = t, as_blocks = t;
    expected.noalias() -= a * b.transpose();
    // As block_sparse_cholesky.cc wrote it before, for blocks of any size up to 3.
    as_blocks.topLeftCorner<3, 3>().noalias() -= a.topLeftCorner<3, 3>() * b.topLeftCorner<3, 3>().transpose();
    SubtractProductTransposed3(a, b, &t);
    differing += std::memcmp(expected.data(), t.data(), sizeof(double) * 9) != 0 ? 1 : 0;
    differing += std::memcmp(as_blocks.data(), t.data(), sizeof(double) * 9) != 0 ? 1 : 0;
  }
  EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace mocapsolve
