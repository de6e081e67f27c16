#pragma once
// Where a product shows its alarm history in the object dictionary:
//  - A6B: 10F3h Diagnosis history (L8905-L9146). 01h = 14 messages, 02h = subindex of the newest
//    (06h..13h, 0 when empty), 03h write 00h clears all (other values: abort 06090030h), 04h = 0,
//    05h flags (bit 0 emergency enable, bits 1-2 read 1, bit 5 = history empty/cleared), 06h..13h
//    messages of 16 bytes: Diag code (603Fh << 16 | E800h), flags 0002h, text ID (main << 8 | sub),
//    time stamp 0 (L9106-L9134).
//  - DS5C1: monitors U1-12 (errors since power-on), U1-14 (alarms ever), U1-16..U1-20 (2nd..6th
//    latest alarm code) at 3100h + n (L7380, L9072-L9100), written only where the dictionary has them.
// The history itself is an AlarmLog that survives power-on; the objects are re-published from it.
#include <cstdint>
#include <memory>

#include "vdrive/drive/alarms/alarm_log.hpp"
#include "vdrive/drive/alarms/alarm_rules.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::drive {

class AlarmHistory {
public:
  virtual ~AlarmHistory() = default;
  virtual void record(const profile::AlarmSpec& alarm) = 0;  // an alarm whose `history` is set occurred
  virtual void power_on() = 0;                               // re-publish after the store was reset
  virtual const AlarmLog& log() const = 0;
  // The alarm and the warning now shown (nullptr: none), after every change (DS5C1 U1-00/U1-01).
  virtual void current(const profile::AlarmSpec* /*alarm*/, const profile::AlarmSpec* /*warning*/) {}
  // The product's emergency-enable switch (A6B 10F3h-05h bit 0); true where there is none.
  virtual bool emergency_enabled() const { return true; }
};

// nullptr for HistoryKind::None. Installs the write hooks the history needs on `store` (A6B 10F3h);
// the hooks share ownership of the history, so they stay valid however long the store lives.
std::shared_ptr<AlarmHistory> make_alarm_history(HistoryKind kind, od::ObjectStore& store);

}  // namespace vdrive::drive
