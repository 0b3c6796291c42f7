// The value of rank k (0-based) of values that are all >= 0, the one std::nth_element puts
// at k, found from the values' bits: a non-negative double's bit pattern orders as its
// value (sign 0, then exponent, then mantissa), so one pass counts the values per top 12
// bits (the exponent), the bucket holding rank k is copied out, narrowed by the next 8 bits
// when large, and only what is left goes to std::nth_element. Two or three passes of
// counting and copying against introselect's partitions of the whole; ranks do not depend
// on how equal values are ordered, so the value is the selection's, bit for bit. When any
// value is not a non-negative finite number (a sign bit, -0.0 included, an infinity or a
// NaN) or there are few, the whole is selected by std::nth_element, as before this was
// written. *values is reordered either way; *scratch is working space.
#ifndef MOCAPSOLVE_SIGNAL_SELECT_NON_NEGATIVE_H_
#define MOCAPSOLVE_SIGNAL_SELECT_NON_NEGATIVE_H_

#include <cstddef>
#include <vector>

namespace mocapsolve {

// k < values->size().
double SelectNonNegative(std::vector<double>* values, size_t k, std::vector<double>* scratch);

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_SIGNAL_SELECT_NON_NEGATIVE_H_
