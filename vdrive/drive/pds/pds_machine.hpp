#pragma once
// The CiA 402 power drive system (PDS) finite state automaton of IEC 61800-7-201 as the three
// products implement it: states, transitions 0-16, the controlword commands, the statusword state
// bits (0-6), and which stop runs while the state changes.
//   A6B L9415-L9781 (transitions), L9849-L9906 (commands), L10023-L10039 (statusword), L26278-L27757
//   (option codes); DS5C1 L5968-L6048, L9380-L9439, L4379-L4509; DS1000A-EC L844-L1082, L5542-L5582.
//
// Product behaviour this reproduces:
// - Shutdown / Disable voltage / Disable operation decelerate FIRST with the state still Operation
//   enabled, and change state once the axis is stopped (A6B L27240-L27246, L27362-L27368; DS5C1
//   L4445-L4472). Quick stop enters Quick stop active at once (L27094-L27100); 605Ah 0-3 then go
//   on to Switch on disabled, 5-7 stay there (transition 16 back with Enable operation).
// - An alarm enters Fault reaction active and reaches Fault once stopped (L27606-L27614); 605Eh
//   governs only the EtherCAT alarms (A6B Err80/81/85/88 L27538-L27570, DS5C1 E-8xx L9587-L9604),
//   the others stop by their own reaction through the vendor's alarm sequence (VendorStop).
// - Switched on needs main power (A6B L9432-L9434; transition 3), its loss gives transition 6
//   and, while enabled, 6007h's reaction (L26567-L26591). STO (A6B, L9436) and the DS1000-EC TO
//   input (L5566-L5572) force Switch on disabled without a fault and hold it there.
// - Fault reset acts on the 0->1 edge of bit 7 only, when the alarm manager allows it (A6B
//   L34001-L34090). While bit 7 is 1 no other command is decoded (every other row of the command
//   table has bit 7 = 0, L9849-L9906).
// - The ESM falling to Init forces Switch on disabled from Ready/Switched on (transitions 7 and 10,
//   A6B L9661-L9707, DS5C1 L5989-L5992); in OE/QSA the ESM change is an alarm (Err88.2, E-882, FF80h).
//
// No allocation, no lookups and no locks per step.
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/drive_types.hpp"
#include "vdrive/drive/pds/option_codes.hpp"
#include "vdrive/drive/pds/stop_kind.hpp"
#include "vdrive/drive/pds/vendor_stop.hpp"

namespace vdrive::drive {

struct PdsConditions {
  bool main_power = true;         // high-level (main) power present -> 6041h bit 4; A6B: Switched on needs it
  bool torque_off = false;        // STO (A6B) / TO input (DS1000A-EC): forced to Switch on disabled, no fault
  bool fault = false;             // an alarm is active (becoming true -> transition 13)
  profile::AlarmReaction fault_reaction{};   // reaction of the newest alarm (None: PDS unchanged)
  bool fault_is_communication = false;       // EtherCAT alarm: 605Eh applies (A6B Err80-88, DS5C1 E-8xx)
  bool fault_reset_allowed = false;          // the alarm manager allows clearing now (causes gone, A6B AL ack done)
  bool cleared_by_drive = false;  // the drive cleared every alarm itself (DS5C1 F0-00 / 4000h): Fault -> Switch on disabled (L7400-L7402)
  bool stopped = false;           // axis at standstill: StopSequence::done(s) of this step's sample
  bool esm_init = false;          // EtherCAT state machine is in Init (transitions 7/10 on A6B/DS5C1)
  std::int8_t mode = 0;           // active mode 6061h (stop ramp choice)
};

class PdsMachine {
public:
  explicit PdsMachine(const DriveContext& ctx);   // resolves 605Ah-605Eh and 6007h

  void power_on();                  // Not ready to switch on -> Switch on disabled (transitions 0, 1)
  void step(std::uint16_t controlword, const PdsConditions& c);   // one control step

  PdsState state() const { return state_; }
  std::uint16_t statusword() const; // bits 0-6 (bit 4 voltage enabled, bit 5 quick stop) only
  bool power_stage_on() const;      // motor energised: OE, QSA, FRA unless the running stop frees it
  bool motion_allowed() const { return state_ == PdsState::OperationEnabled && stop_ == StopKind::None; }

  // The stop running now (None otherwise) and, for DriveSide, what it does. Start StopSequence with
  // both when stop_started() (a new stop began, or a fault replaced the running one).
  StopKind stop() const { return stop_; }
  DriveSideAction drive_side_action() const { return action_; }
  bool stop_started() const { return stop_started_; }

  bool enabled_event() const { return enabled_event_; }          // transition 4 or 16 in the last step
  bool fault_reset_event() const { return fault_reset_event_; }  // transition 15 in the last step
  // Main power was lost while enabled with 6007h = 1: the engine raises the product's alarm for it
  // (A6B Err88.0 after the 605Eh deceleration, L26776-L26780).
  bool abort_connection_fault() const { return abort_connection_fault_; }

  const OptionCodes& option_codes() const { return codes_; }
  const VendorStop& vendor_stop() const { return vendor_; }

private:
  enum class Command : std::uint8_t { None, DisableVoltage, QuickStop, Shutdown, SwitchOn, EnableOperation };
  static Command decode(std::uint16_t controlword);

  void step_enabled(Command cmd, const PdsConditions& c, bool power_lost);
  void step_quick_stop_active(Command cmd, const PdsConditions& c);
  void begin_fault(const PdsConditions& c);
  void begin_stop(StopKind kind, DriveSideAction action, PdsState after);
  void enter_quick_stop(const PdsConditions& c, bool power_lost);
  void set_stop(StopKind kind, DriveSideAction action);
  void end_stop(PdsState next);
  StopKind fault_stop(const PdsConditions& c, DriveSideAction& action) const;

  OptionCodes codes_;
  VendorStop vendor_;
  PdsState state_ = PdsState::NotReadyToSwitchOn;
  StopKind stop_ = StopKind::None;
  DriveSideAction action_ = DriveSideAction::None;
  PdsState after_stop_ = PdsState::SwitchOnDisabled;   // where a running stop ends
  bool quick_stop_stays_ = false;                      // 605Ah 5-7 latched at transition 11
  bool quick_stop_done_ = false;
  bool main_power_ = true;
  bool fault_reset_bit_ = false;
  bool faulting_ = false;
  bool stop_started_ = false;
  bool enabled_event_ = false;
  bool fault_reset_event_ = false;
  bool abort_connection_fault_ = false;
};

}  // namespace vdrive::drive
