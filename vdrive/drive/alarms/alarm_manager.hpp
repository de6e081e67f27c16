#pragma once
// The drive's vendor alarms: which alarms of the product's table
// (profiles/<id>/alarms.yaml) are active, what 603Fh and 1001h show, the emergency message each
// alarm and the final clear send, the alarm history, and whether a fault reset may clear them.
//
//  - Raising: 603Fh = the newest alarm's code (A6B L33970-L34000), 1001h per the product's rule
//    (alarm_rules.hpp), an emergency per new alarm (A6B: 603Fh, 1001h, data[0] = sub code,
//    L4643-L4842; none for warnings, L4561), a history entry where the product keeps one.
//  - Clearing (fault reset edge; A6B 8-4 L34001-L34060, DS5C1 L7386-L7412): refused during Fault
//    reaction active, while any active alarm's cause is still present (L34048-L34050), and for
//    alarms with an AL status code until the master acknowledged the AL error (AL control bit 4,
//    L34013-L34017, DS5C1 L7394-L7396). Non-clearable alarms stay until power_on(). A6B Err16.0
//    clears only 10 s after it occurred; a reset asked for earlier is carried out then (L32918-L32920).
//    When no alarm is left: emergency 0000h/00h/0... (L4848-L4885), 603Fh = 1001h = 0.
//
// Per control step nothing allocates: alarms are resolved with find() at construction time, state
// is a table sized at construction, the emergency sink must not allocate either.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "common/clock.hpp"
#include "ethercat/emergency.hpp"
#include "vdrive/drive/alarms/alarm_history.hpp"
#include "vdrive/drive/alarms/alarm_rules.hpp"
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class AlarmManager {
public:
  using EmergencySink = std::function<void(const ecat::coe::Emergency&)>;

  AlarmManager(const DriveContext& ctx, EmergencySink sink);

  // Control power on: no alarm active, 603Fh = 1001h = 0; the history objects are published again
  // from the drive's EEPROM copy (A6B L8929-L8931). Call after the store was reset to defaults.
  void power_on();

  const profile::AlarmSpec* find(std::string_view code) const { return ctx_.profile.find_alarm(code); }

  // Raises `alarm` (from this product's table). False and no effect if it is already active.
  bool raise(const profile::AlarmSpec& alarm, Nanos now);
  // As raise(), with the emergency's data bytes given by the detector (A6B Err81.7: SyncManager
  // details, L4889-L4960).
  bool raise(const profile::AlarmSpec& alarm, Nanos now, const std::array<std::uint8_t, 5>& data);

  // The simulated cause is (still) present; a present cause blocks clearing. A warning whose cause
  // goes away disappears by itself.
  void set_cause(const profile::AlarmSpec& alarm, bool present);

  bool active() const { return active_count_ > 0; }      // an alarm (not a warning): PDS Fault
  bool warning() const { return warning_count_ > 0; }    // 6041h bit 7
  bool is_active(const profile::AlarmSpec& alarm) const;
  const profile::AlarmSpec* newest() const { return newest_; }
  // The newest active alarm's position in the product's alarm table (profile.alarms), or -1: which
  // alarm it is where several share one 603Fh (A6B Err81.0-81.6 are all FF51h).
  int newest_index() const;
  std::uint16_t error_code() const;                      // 603Fh (0 = none)
  std::uint8_t error_register() const { return error_register_; }   // 1001h
  bool is_communication(const profile::AlarmSpec& alarm) const { return is_communication_alarm(alarm); }

  // Would a fault reset now leave no alarm active (so the PDS goes Fault -> Switch on disabled)?
  bool reset_allowed(bool al_error_pending, bool fault_reaction_active, Nanos now) const;
  // Fault reset edge (6040h bit 7 0->1) in Fault: clears the clearable alarms if nothing blocks it.
  // True if no alarm is left. Refused only because an alarm is too young (Err16.0): remembered,
  // see complete_pending_reset().
  bool reset(bool al_error_pending, Nanos now);
  bool reset_pending() const { return reset_pending_; }
  // Call every control step while in Fault: carries out a remembered reset once it may. True when
  // that left no alarm active (the engine then takes transition 15).
  bool complete_pending_reset(bool al_error_pending, bool fault_reaction_active, Nanos now);
  // Clear from the drive's own side, which needs no AL acknowledge: A6B PANATERM (L34028-L34030),
  // DS5C1 panel F0-00 / SDO 4000h = 1 (L7400-L7412). True if no alarm is left.
  bool clear_from_drive(bool fault_reaction_active, Nanos now);

  const profile::AlarmRulesSpec& rules() const { return rules_; }
  const AlarmHistory* history() const { return history_.get(); }   // nullptr: the product keeps none

private:
  struct State {
    bool active = false;
    bool cause = false;
    Nanos since = 0;
    std::uint64_t order = 0;
  };
  enum class Block : std::uint8_t { None, TooYoung, Other };

  const State* state_of(const profile::AlarmSpec& alarm) const;
  State* state_of(const profile::AlarmSpec& alarm);
  bool raise_with(const profile::AlarmSpec& alarm, Nanos now, const std::array<std::uint8_t, 5>* data);
  Block blocked(bool al_error_pending, bool fault_reaction_active, Nanos now) const;
  bool clear_clearable();
  void refresh();
  void publish();
  void emit(const ecat::coe::Emergency& e) const;

  const DriveContext& ctx_;
  EmergencySink sink_;
  const profile::AlarmRulesSpec& rules_;  // the product's drive.alarm_rules
  std::shared_ptr<AlarmHistory> history_;
  ObjectRef<std::uint16_t> error_code_, error_register_ref_;
  std::vector<State> states_;          // one per profile.alarms entry
  std::uint64_t next_order_ = 1;
  std::size_t active_count_ = 0, warning_count_ = 0;
  const profile::AlarmSpec* newest_ = nullptr;           // newest active alarm
  const profile::AlarmSpec* newest_warning_ = nullptr;
  std::uint8_t error_register_ = 0;
  bool reset_pending_ = false;
};

}  // namespace vdrive::drive
