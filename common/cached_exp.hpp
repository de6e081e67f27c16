#pragma once
// exp(x), remembered for the last x. The drive's and the plant's first-order lags take
// exp(-dt / tau) every control step with the same dt and tau; those libm calls were ~3 % of a cycle.
// Exact: the same x gives the same bits.
#include <cmath>

namespace vdrive {

class CachedExp {
public:
  double operator()(double x) {
    if (x != x_) {  // NaN never equals itself: recomputed, as exp(NaN) must be
      x_ = x;
      y_ = std::exp(x);
    }
    return y_;
  }

private:
  double x_ = 0.0;
  double y_ = 1.0;  // exp(0)
};

}  // namespace vdrive
