// Selection by the bits of non-negative values: the value of rank k is the one sorting
// gives, bit for bit, for values spread over many exponents or packed into one, with ties,
// zeros and subnormals, and for values it must hand to std::nth_element (negative, -0.0,
// infinite, NaN).
#include "signal/select_non_negative.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

namespace mocapsolve {
namespace {

uint64_t Bits(double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

class Random {
 public:
  double Uniform() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

 private:
  uint64_t state_ = 777;
};

// Every rank of the values checked against a sort: same bits.
void ExpectEveryRankAsSorted(const std::vector<double>& values, const char* what) {
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> work, scratch;
  for (size_t k = 0; k < values.size(); k += 1 + values.size() / 97) {
    work = values;
    const double got = SelectNonNegative(&work, k, &scratch);
    ASSERT_EQ(Bits(got), Bits(sorted[k])) << what << ": rank " << k << " of " << values.size();
  }
  work = values;
  const size_t mid = values.size() / 2;
  EXPECT_EQ(Bits(SelectNonNegative(&work, mid, &scratch)), Bits(sorted[mid])) << what;
}

TEST(SelectNonNegative, EveryRankIsTheSortedValue) {
  Random random;
  for (const size_t n : {1u, 7u, 255u, 256u, 1000u, 5000u, 20000u}) {
    std::vector<double> wide(n), narrow(n), ties(n), squares(n);
    for (size_t i = 0; i < n; ++i) {
      wide[i] = std::pow(10.0, -12.0 + 16.0 * random.Uniform());       // Many exponents.
      narrow[i] = 1.0 + random.Uniform() * 1e-3;                         // One exponent, few top bits.
      ties[i] = std::floor(random.Uniform() * 5.0) * 0.25;               // Ties and zeros.
      const double d = random.Uniform() - 0.5;
      squares[i] = i % 11 == 0 ? 0.0 : i % 13 == 0 ? 1e-310 : d * d;    // Zeros and subnormals.
    }
    ExpectEveryRankAsSorted(wide, "wide");
    ExpectEveryRankAsSorted(narrow, "narrow");
    ExpectEveryRankAsSorted(ties, "ties");
    ExpectEveryRankAsSorted(squares, "squares");
  }
}

TEST(SelectNonNegative, ValuesWithoutABitOrderAreSelectedWhole) {
  Random random;
  std::vector<double> values(2000);
  for (double& v : values) v = random.Uniform();
  std::vector<double> scratch;
  for (const double odd : {-1.0, -0.0, std::numeric_limits<double>::infinity()}) {
    std::vector<double> with = values;
    with[17] = odd;
    std::vector<double> sorted = with;
    std::sort(sorted.begin(), sorted.end());
    for (const size_t k : {size_t{0}, size_t{1000}, size_t{1999}}) {
      std::vector<double> work = with;
      EXPECT_EQ(SelectNonNegative(&work, k, &scratch), sorted[k]) << odd << " rank " << k;
    }
  }
  // A NaN: what std::nth_element gives.
  std::vector<double> with = values;
  with[5] = std::nan("");
  std::vector<double> expected = with;
  std::nth_element(expected.begin(), expected.begin() + 1000, expected.end());
  EXPECT_EQ(Bits(SelectNonNegative(&with, 1000, &scratch)), Bits(expected[1000]));
}

}  // namespace
}  // namespace mocapsolve
