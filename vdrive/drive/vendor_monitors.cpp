#include "vdrive/drive/vendor_monitors.hpp"

#include <limits>

#include "common/round.hpp"

namespace vdrive::drive {

namespace {

double quantity_of(profile::MonitorQuantity q, const MonitorValues& v) {
  switch (q) {
    case profile::MonitorQuantity::MotorSpeedRpm: return v.motor_speed_rpm;
    case profile::MonitorQuantity::SpeedDemandRpm: return v.speed_demand_rpm;
    case profile::MonitorQuantity::TorqueDemandPercent: return v.torque_demand_percent;
    case profile::MonitorQuantity::TorqueActualPercent: return v.torque_actual_percent;
    case profile::MonitorQuantity::MotorCurrentA: return v.motor_current_a;
  }
  return 0.0;
}

}  // namespace

VendorMonitors::VendorMonitors(od::ObjectStore& store, const std::vector<profile::MonitorSpec>& specs) {
  monitors_.reserve(specs.size());
  for (const profile::MonitorSpec& s : specs) {
    ObjectRef<std::int64_t> object(store, s.index, s.subindex);
    if (object.present()) monitors_.push_back({s.quantity, s.scale, object});
  }
}

// A negative value in an unsigned object (the DS5C1's U0 monitors are typed U16 for want of a type
// in the manual) keeps its two's-complement bits, as a 16-bit register of the drive would show it.
void VendorMonitors::publish(const MonitorValues& v) {
  constexpr double kLimit = static_cast<double>(std::numeric_limits<std::int32_t>::max());
  for (Monitor& m : monitors_) {
    const double counts = quantity_of(m.quantity, v) / m.per_count;
    m.object.set(round_to_int64(counts > kLimit ? kLimit : counts < -kLimit ? -kLimit : counts));
  }
}

}  // namespace vdrive::drive
