#include "vdrive/drive/alarms/diagnosis_history.hpp"

#include <algorithm>

#include "ethercat/little_endian.hpp"
#include "vdrive/drive/alarms/alarm_code.hpp"

namespace vdrive::drive {

namespace {
// 10F3h-05h bits (L9076-L9102).
constexpr std::uint16_t kEmergencyEnable = 1u << 0;
constexpr std::uint16_t kFixedOnes = (1u << 1) | (1u << 2);   // "Not supported: 1 fixed"
constexpr std::uint16_t kCleared = 1u << 5;                   // no history / cleared, until the next alarm
}  // namespace

DiagnosisHistory::DiagnosisHistory(od::ObjectStore& store)
    : store_(store), entries_(store, kIndex, 0x00), max_messages_(store, kIndex, 0x01), newest_(store, kIndex, 0x02),
      acknowledged_(store, kIndex, 0x03), new_available_(store, kIndex, 0x04), flags_(store, kIndex, 0x05) {
  for (std::uint8_t i = 0; i < kMessages; ++i)
    messages_[i] = store.dictionary().find(kIndex, static_cast<std::uint8_t>(kFirstMessage + i));
}

void DiagnosisHistory::power_on() {
  entries_.set(0x13);        // L9028-L9030
  max_messages_.set(kMessages);
  acknowledged_.set(0);      // reads 0 (L9052)
  new_available_.set(0);     // not supported, 0 (L9066-L9068)
  // 05h is kept in EEPROM (L9072). The dictionary has no default for it (chapter 9 prints none), so
  // a value without the fixed ones is the blank default: the factory setting is "emergency enabled"
  // (L4575). A saved value always carries the fixed ones, because the drive publishes them.
  if ((flags_.get() & kFixedOnes) != kFixedOnes) flags_.set(kEmergencyEnable);
  write_flags(log_.size() == 0);
  publish();
}

void DiagnosisHistory::record(const profile::AlarmSpec& alarm) {
  log_.record(alarm);
  write_flags(false);
  publish();
}

void DiagnosisHistory::clear() {
  log_.clear();
  write_flags(true);
  publish();
}

bool DiagnosisHistory::emergency_enabled() const {
  // A dictionary without 10F3h-05h (or its blank default) leaves the factory setting: enabled.
  const std::uint16_t flags = flags_.get();
  if (!flags_.present() || (flags & kFixedOnes) != kFixedOnes) return true;
  return (flags & kEmergencyEnable) != 0;
}

void DiagnosisHistory::write_flags(bool cleared) {
  std::uint16_t flags = static_cast<std::uint16_t>((flags_.get() & kEmergencyEnable) | kFixedOnes);
  if (cleared) flags |= kCleared;
  flags_.set(flags);
}

void DiagnosisHistory::publish() {
  // Oldest in 06h, newest at 06h + n - 1 (L8948-L8982); unused messages read 0.
  for (std::uint8_t i = 0; i < kMessages; ++i) {
    if (!messages_[i]) continue;
    const std::span<std::uint8_t> bytes = store_.raw(*messages_[i]);
    std::fill(bytes.begin(), bytes.end(), 0);
    if (i >= log_.size() || bytes.size() < 8) continue;
    const profile::AlarmSpec& alarm = log_.at(i);
    const AlarmCode code = parse_alarm_code(alarm.code);
    // "00 E8 10 FF 02 00 ..." (L9112): Diag code E800h | 603Fh << 16, flags 0002h, text ID main/sub.
    bytes[0] = 0x00;
    bytes[1] = 0xE8;
    ecat::put_le16(bytes, 2, alarm.error_code);
    bytes[4] = 0x02;
    bytes[5] = 0x00;
    // Text ID: high byte main, low byte sub (L9130-L9132). The L9112 example prints 0000h there; we
    // follow the text. The main number is coded as in 603Fh (16 -> 10h, L33944-L33948).
    bytes[6] = code.sub;
    bytes[7] = code.main;
  }
  newest_.set(log_.size() == 0 ? 0 : static_cast<std::uint8_t>(kFirstMessage + log_.size() - 1));
}

void DiagnosisHistory::install_hook(const std::shared_ptr<DiagnosisHistory>& self, od::ObjectStore& store) {
  if (!store.dictionary().find(kIndex)) return;
  store.on_write(kIndex, [self](const od::EntryDesc& e, std::span<const std::uint8_t> data) {
    if (e.subindex != 0x03) return od::SdoAbort::Ok;
    if (data.empty() || data[0] != 0) return od::SdoAbort::ValueRangeExceeded;   // L9058-L9060
    self->clear();
    return od::SdoAbort::Ok;
  });
}

}  // namespace vdrive::drive
