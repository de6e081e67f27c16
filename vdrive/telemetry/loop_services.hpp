#pragma once
// LoopServices: two LoopServices polled as one, since the event loop takes a single service
// (vdrive run polls its fault control and the telemetry sampler). Either may be null.
#include <algorithm>
#include <limits>

#include "vdrive/runtime/loop_service.hpp"

namespace vdrive::telemetry {

class LoopServices final : public runtime::LoopService {
public:
  LoopServices(runtime::LoopService* first, runtime::LoopService* second) : first_(first), second_(second) {}
  void poll(Nanos now) override {
    if (first_ != nullptr) first_->poll(now);
    if (second_ != nullptr) second_->poll(now);
  }
  Nanos next_deadline() const override {
    Nanos d = std::numeric_limits<Nanos>::max();
    if (first_ != nullptr) d = std::min(d, first_->next_deadline());
    if (second_ != nullptr) d = std::min(d, second_->next_deadline());
    return d;
  }

private:
  runtime::LoopService* first_;
  runtime::LoopService* second_;
};

}  // namespace vdrive::telemetry
