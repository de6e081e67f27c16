#pragma once
// "Condition true for at least T": the CiA 402 windows (6067h/6068h target reached, 6065h/6066h
// following error, 606Dh/606Eh velocity window, 606Fh/6070h threshold) all have this shape.
#include "common/clock.hpp"

namespace vdrive::drive {

class HoldTimer {
public:
  // True once `condition` has held continuously for at least `hold` (0 = at once); false as soon
  // as it fails.
  bool update(bool condition, Nanos now, Nanos hold) {
    if (!condition) {
      holding_ = false;
      return false;
    }
    if (!holding_) {
      holding_ = true;
      since_ = now;
    }
    return now - since_ >= hold;
  }
  void reset() { holding_ = false; }

private:
  bool holding_ = false;
  Nanos since_ = 0;
};

}  // namespace vdrive::drive
