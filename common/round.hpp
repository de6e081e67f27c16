#pragma once
// std::llround without the libm call: glibc's lround is ~20 instructions behind a PLT jump, and the
// drive and the DC unit round a few thousand values per bus cycle. Same result for every input:
// half-way cases away from zero; |x| >= 2^52 (already whole), NaN and out of range go to llround.
#include <cmath>
#include <cstdint>

namespace vdrive {

inline std::int64_t round_to_int64(double x) {
  if (!(std::fabs(x) < 0x1p52)) return std::llround(x);
  const auto whole = static_cast<std::int64_t>(x);   // toward zero, exact here
  const double frac = x - static_cast<double>(whole);  // exact: the bits of x below the point
  return whole + (frac >= 0.5) - (frac <= -0.5);
}

}  // namespace vdrive
