#pragma once
// The A6B's alarm history object 10F3h Diagnosis history (L8905-L9146); see alarm_history.hpp for
// the layout. Only alarms whose table row says history = Yes are recorded (L32912-L32916).
#include <array>

#include "vdrive/drive/alarms/alarm_history.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class DiagnosisHistory final : public AlarmHistory {
public:
  static constexpr std::uint16_t kIndex = 0x10F3;
  static constexpr std::uint8_t kFirstMessage = 0x06;   // Diagnosis message 1
  static constexpr std::uint8_t kMessages = 14;         // 06h..13h (L9036-L9038)

  explicit DiagnosisHistory(od::ObjectStore& store);

  void record(const profile::AlarmSpec& alarm) override;
  void power_on() override;
  const AlarmLog& log() const override { return log_; }
  bool emergency_enabled() const override;

  // 10F3h-03h written with 00h: every message is cleared and flags bit 5 set (L9048-L9060, L9094-L9100).
  void clear();

  // Install the 10F3h write hook on `store` (03h: clear / refuse with 06090030h).
  static void install_hook(const std::shared_ptr<DiagnosisHistory>& self, od::ObjectStore& store);

private:
  void publish();
  void write_flags(bool cleared);

  od::ObjectStore& store_;
  AlarmLog log_{kMessages};
  ObjectRef<std::uint8_t> entries_, max_messages_, newest_, acknowledged_, new_available_;
  ObjectRef<std::uint16_t> flags_;
  std::array<const od::EntryDesc*, kMessages> messages_{};
};

}  // namespace vdrive::drive
