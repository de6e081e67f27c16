#pragma once
// Statusword bit 13 "following error" in csp and ip: |6062h - 6064h| beyond 6065h for longer than
// 6066h ms (A6B L14279-L14407, DS1000A-EC L1341-L1357, DS5C1 csp table L2735-L2888). A window of
// FFFFFFFFh switches the check off (CiA 402). Only the statusword: the vendor alarm on excess
// deviation is the engine's supervision.
#include <cmath>
#include <cstdint>

#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/hold_timer.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class CyclicFollowingError {
public:
  explicit CyclicFollowingError(od::ObjectStore& o) : window_(o, 0x6065, 0, 0xFFFFFFFFu), time_ms_(o, 0x6066) {}

  bool update(const AxisSample& s) {
    const std::uint32_t window = window_.get();
    const bool beyond = window != 0xFFFFFFFFu && std::abs(s.position_demand - s.position) > static_cast<double>(window);
    active_ = timer_.update(beyond, s.time, static_cast<Nanos>(time_ms_.get()) * 1'000'000);
    return active_;
  }
  void reset() {
    timer_.reset();
    active_ = false;
  }
  bool active() const { return active_; }

private:
  ObjectRef<std::uint32_t> window_;
  ObjectRef<std::uint16_t> time_ms_;
  HoldTimer timer_;
  bool active_ = false;
};

}  // namespace vdrive::drive
