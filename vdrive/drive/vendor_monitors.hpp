#pragma once
// The vendor monitor objects a profile names (`drive.monitors`, e.g. the DS5C1's U0 group at
// 3000h + n, L5787-L5790, App. 1.3 L9017-L9066), written with the drive's live values at the end
// of every control step, as 6064h/606Ch/6077h are. Resolved once; publishing neither searches the
// dictionary nor allocates. An object the dictionary lacks is skipped.
#include <cstdint>
#include <vector>

#include "vdrive/drive/object_ref.hpp"
#include "vdrive/profile/drive_spec.hpp"

namespace vdrive::drive {

// The drive's live quantities in the units MonitorQuantity names.
struct MonitorValues {
  double motor_speed_rpm = 0.0;
  double speed_demand_rpm = 0.0;
  double torque_demand_percent = 0.0;
  double torque_actual_percent = 0.0;
  double motor_current_a = 0.0;
};

class VendorMonitors {
public:
  VendorMonitors(od::ObjectStore& store, const std::vector<profile::MonitorSpec>& specs);

  bool empty() const { return monitors_.empty(); }
  void publish(const MonitorValues& v);

private:
  struct Monitor {
    profile::MonitorQuantity quantity;
    double per_count;
    ObjectRef<std::int64_t> object;
  };
  std::vector<Monitor> monitors_;
};

}  // namespace vdrive::drive
