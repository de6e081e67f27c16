#pragma once
// 6060h (requested) -> 6061h (in effect) with each product's rules: 0 after a valid mode keeps it
// (A6B L10357-L10468, DS5C1 L6098-L6102), unsupported values are refused (A6B Err88.1, DS5C1
// E-881) or ignored (DS1000A-EC L1604-L1640), some switches are forbidden while enabled (DS5C1
// PP->CSP, L4367-L4377), some products switch only outside Operation enabled (DS1000A-EC
// L1594-L1600), and a switch takes time (A6B and DS5C1 about 2 ms; 6061h shows the old mode until
// the new one runs).
#include <cstdint>

#include "common/clock.hpp"
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class ModeSelector {
public:
  explicit ModeSelector(const DriveContext& ctx);

  void power_on();
  // One control step. `enabled`: Operation enabled (a switch there follows the product's rules).
  void step(Nanos now, bool enabled);

  std::int8_t active() const { return active_; }
  bool changed() const { return changed_; }           // active() changed in the last step
  bool switching() const { return pending_; }         // a switch is under way
  bool invalid_request() const { return invalid_; }   // 6060h holds a value the product does not run
  bool supported(std::int8_t mode) const;

private:
  const DriveContext& ctx_;
  ObjectRef<std::int8_t> requested_, display_;
  std::int8_t active_ = 0;
  std::int8_t target_ = 0;
  bool pending_ = false;
  Nanos switch_done_ = 0;
  bool changed_ = false;
  bool invalid_ = false;
};

}  // namespace vdrive::drive
