#include "signal/select_non_negative.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace mocapsolve {
namespace {

// Below this many values the whole selection is as quick as counting.
constexpr size_t kMinCounted = 256;
// A bucket larger than this is narrowed by the next 8 bits before its selection.
constexpr size_t kMinNarrowed = 512;

uint64_t Bits(double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}

double SelectWhole(std::vector<double>* values, size_t k) {
  std::nth_element(values->begin(), values->begin() + k, values->end());
  return (*values)[k];
}

}  // namespace

double SelectNonNegative(std::vector<double>* values, size_t k, std::vector<double>* scratch) {
  const std::vector<double>& v = *values;
  if (v.size() < kMinCounted) return SelectWhole(values, k);
  // Top 12 bits: 0..2046 for non-negative finite values; 2047 (infinity, NaN) and above
  // (a sign bit) fall back to the whole selection.
  uint32_t counts[2048] = {};
  for (const double x : v) {
    const uint64_t top = Bits(x) >> 52;
    if (top >= 2047) return SelectWhole(values, k);
    ++counts[top];
  }
  size_t below = 0;
  uint64_t bucket = 0;
  while (below + counts[bucket] <= k) below += counts[bucket++];
  scratch->clear();
  for (const double x : v) {
    if (Bits(x) >> 52 == bucket) scratch->push_back(x);
  }
  k -= below;
  if (scratch->size() > kMinNarrowed) {
    uint32_t next[256] = {};
    for (const double x : *scratch) ++next[(Bits(x) >> 44) & 255];
    below = 0;
    uint64_t sub = 0;
    while (below + next[sub] <= k) below += next[sub++];
    size_t kept = 0;
    for (const double x : *scratch) {
      if (((Bits(x) >> 44) & 255) == sub) (*scratch)[kept++] = x;
    }
    scratch->resize(kept);
    k -= below;
  }
  return SelectWhole(scratch, k);
}

}  // namespace mocapsolve
