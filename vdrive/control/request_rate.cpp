#include "vdrive/control/request_rate.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace vdrive::control {

RequestRate::RequestRate(double per_second, double burst) : per_second_(per_second), burst_(burst), tokens_(burst) {}

bool RequestRate::take_at(Nanos now, Nanos* wait) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (started_ && now > last_) tokens_ = std::min(burst_, tokens_ + static_cast<double>(now - last_) * 1e-9 * per_second_);
  if (!started_ || now > last_) last_ = now;
  started_ = true;
  if (tokens_ >= 1.0) {
    tokens_ -= 1.0;
    return true;
  }
  if (wait != nullptr) *wait = static_cast<Nanos>(std::ceil((1.0 - tokens_) / per_second_ * 1e9));
  return false;
}

std::string RequestRate::refusal(Nanos wait) const {
  return fmt::format("too many requests: at most {:g} a second ({:g} at once); try again in {} ms", per_second_, burst_,
                     std::max<Nanos>(1, (wait + 999'999) / 1'000'000));
}

}  // namespace vdrive::control
