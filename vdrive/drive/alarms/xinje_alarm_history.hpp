#pragma once
// The DS5C1's alarm history, shown by its U1 monitors (U1-xx = 3100h + xx, L7380; list L9072-L9100):
// U1-00 the current alarm code ("0x3100: 00（当前报警代码）", L7380-L7384), U1-01 the current warning
// code (L9073), U1-12 alarms since this power-on, U1-14 alarms ever recorded, U1-16..U1-20 the
// 2nd..6th latest alarm codes. The manual does not say how a code is coded there; we show the
// printed number, all three digits (E-222 -> 222), which 603Fh's 8-bit field cannot hold
// (docs/products.md). The objects are published only where the dictionary has them (8.3.1 lists
// 3100h and 3101h, L5824-L5825).
#include <array>

#include "vdrive/drive/alarms/alarm_history.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class XinjeAlarmHistory final : public AlarmHistory {
public:
  static constexpr std::size_t kDepth = 6;   // latest .. 6th latest (L9088-L9092)

  explicit XinjeAlarmHistory(od::ObjectStore& store);

  void record(const profile::AlarmSpec& alarm) override;
  void power_on() override;
  void current(const profile::AlarmSpec* alarm, const profile::AlarmSpec* warning) override;
  const AlarmLog& log() const override { return log_; }
  std::uint32_t since_power_on() const { return since_power_on_; }

private:
  void publish();

  AlarmLog log_{kDepth};
  std::uint32_t since_power_on_ = 0;
  ObjectRef<std::uint16_t> current_alarm_, current_warning_, run_count_, total_count_;
  std::array<ObjectRef<std::uint16_t>, kDepth - 1> recent_;   // U1-16..U1-20
};

}  // namespace vdrive::drive
