#include "vdrive/drive/pds/pds_machine.hpp"

namespace vdrive::drive {

namespace {

constexpr bool powered_state(PdsState s) {
  return s == PdsState::OperationEnabled || s == PdsState::QuickStopActive || s == PdsState::FaultReactionActive;
}

// Ordering of the states a running stop can end in: a later, "lower" command wins.
constexpr int depth(PdsState s) {
  switch (s) {
    case PdsState::SwitchOnDisabled: return 0;
    case PdsState::ReadyToSwitchOn: return 1;
    default: return 2;
  }
}

// A stop that lets the motor go (servo-side free run / dynamic brake, coast) outranks the CoE
// ramps: "servo-side deceleration > ... > fault deceleration > other CoE deceleration" (A6B
// L26482-L26502); a lower-ranked cause keeps the accepted deceleration.
constexpr bool outranks(StopKind running, DriveSideAction running_action, StopKind wanted) {
  return running != StopKind::None && stop_frees_motor(running, running_action) &&
         wanted != StopKind::Coast && wanted != StopKind::DriveSide;
}

}  // namespace

PdsMachine::PdsMachine(const DriveContext& ctx) : codes_(ctx), vendor_(ctx) {}

PdsMachine::Command PdsMachine::decode(std::uint16_t cw) {
  // Command table (A6B L9849-L9906, DS5C1 L9382-L9393, DS1000A-EC L962-L984). Bit 7 is 0 in every
  // row but Fault reset.
  if (cw & cw::fault_reset) return Command::None;
  if (!(cw & cw::enable_voltage)) return Command::DisableVoltage;   // 0 x x 0 x
  if (!(cw & cw::quick_stop)) return Command::QuickStop;             // 0 x 0 1 x (active low)
  if (!(cw & cw::switch_on)) return Command::Shutdown;               // 0 x 1 1 0
  if (!(cw & cw::enable_operation)) return Command::SwitchOn;        // 0 0 1 1 1 (also Disable operation)
  return Command::EnableOperation;                                   // 0 1 1 1 1
}

void PdsMachine::power_on() {
  // Transitions 0 and 1 run on their own after control power-on (A6B L9618-L9626).
  state_ = PdsState::SwitchOnDisabled;
  stop_ = StopKind::None;
  action_ = DriveSideAction::None;
  quick_stop_stays_ = quick_stop_done_ = false;
  main_power_ = true;
  fault_reset_bit_ = faulting_ = false;
  stop_started_ = enabled_event_ = fault_reset_event_ = abort_connection_fault_ = false;
  codes_.refresh();
}

std::uint16_t PdsMachine::statusword() const {
  // State coding (A6B L10023-L10039, DS5C1 L9432-L9439, DS1000A-EC L1068-L1082); bit 4 whenever
  // main power is applied (A6B L1749-L1751: xx21h becomes xx31h).
  std::uint16_t bits = 0;
  switch (state_) {
    case PdsState::NotReadyToSwitchOn: return 0x0000;
    case PdsState::SwitchOnDisabled: bits = 0x0040; break;
    case PdsState::ReadyToSwitchOn: bits = 0x0021; break;
    case PdsState::SwitchedOn: bits = 0x0023; break;
    case PdsState::OperationEnabled: bits = 0x0027; break;
    case PdsState::QuickStopActive: bits = 0x0007; break;
    case PdsState::FaultReactionActive: bits = 0x000F; break;
    case PdsState::Fault: bits = 0x0008; break;
  }
  if (main_power_) bits |= sw::voltage_enabled;
  return bits;
}

bool PdsMachine::power_stage_on() const { return powered_state(state_) && !stop_frees_motor(stop_, action_); }

void PdsMachine::set_stop(StopKind kind, DriveSideAction action) {
  if (kind != stop_ || action != action_) stop_started_ = true;
  stop_ = kind;
  action_ = kind == StopKind::DriveSide ? action : DriveSideAction::None;
}

void PdsMachine::end_stop(PdsState next) {
  state_ = next;
  stop_ = StopKind::None;
  action_ = DriveSideAction::None;
}

void PdsMachine::begin_stop(StopKind kind, DriveSideAction action, PdsState after) {
  if (kind == StopKind::Coast) {  // CiA 402 "disable drive function": nothing to wait for
    end_stop(after);
    return;
  }
  set_stop(kind, action);
  after_stop_ = after;
}

StopKind PdsMachine::fault_stop(const PdsConditions& c, DriveSideAction& action) const {
  action = DriveSideAction::None;
  StopKind kind;
  if (c.fault_is_communication) {
    kind = fault_reaction_kind(codes_.fault_reaction(), c.mode, vendor_.present());
  } else if (vendor_.present()) {
    kind = StopKind::DriveSide;  // 3510h / P0-29 for every other alarm (L27568-L27570, L9600-L9604)
  } else {
    switch (c.fault_reaction) {  // the alarm's own reaction (profile alarms.yaml)
      case profile::AlarmReaction::ImmediateStop: kind = StopKind::CurrentLimit; break;
      case profile::AlarmReaction::Deceleration: kind = StopKind::QuickStopRamp; break;
      default: kind = StopKind::Coast; break;
    }
  }
  if (kind == StopKind::DriveSide) action = vendor_.alarm(c.fault_reaction);
  return kind;
}

void PdsMachine::begin_fault(const PdsConditions& c) {
  // Transition 13. Without power there is nothing to stop: 14 follows at once.
  if (!powered_state(state_)) {
    end_stop(PdsState::Fault);
    return;
  }
  DriveSideAction action;
  const StopKind kind = fault_stop(c, action);
  state_ = PdsState::FaultReactionActive;
  if (!outranks(stop_, action_, kind)) set_stop(kind, action);
}

void PdsMachine::enter_quick_stop(const PdsConditions& c, bool power_lost) {
  // Transition 11: Quick stop active at once, decelerating (A6B L27094-L27096).
  const std::int16_t code = codes_.quick_stop();
  quick_stop_stays_ = quick_stop_stays_active(code) && c.main_power && !power_lost;  // 6007h = 3: (*1) L27061
  quick_stop_done_ = false;
  state_ = PdsState::QuickStopActive;
  const StopKind kind = quick_stop_kind(code, c.mode, vendor_.present());
  if (kind == StopKind::Coast) {  // "disable drive function": 11 and 12 at once
    end_stop(PdsState::SwitchOnDisabled);
    return;
  }
  if (!outranks(stop_, action_, kind))
    set_stop(kind, kind == StopKind::DriveSide ? vendor_.servo_off() : DriveSideAction::None);
}

void PdsMachine::step_enabled(Command cmd, const PdsConditions& c, bool power_lost) {
  if (c.torque_off) {  // transition 9: STO / TO cuts the power stage at once (L9689-L9691, L5566-L5572)
    end_stop(PdsState::SwitchOnDisabled);
    return;
  }
  if (power_lost) {  // 6007h Abort connection option code (A6B L26567-L26591; 0 when absent)
    switch (codes_.abort_connection()) {
      case 1: abort_connection_fault_ = true; break;
      case 2: cmd = Command::DisableVoltage; break;   // 605Bh deceleration, transition 9
      case 3: cmd = Command::QuickStop; break;        // 605Ah deceleration, ends in SOD
      default: break;
    }
  }
  const bool stopping = stop_ != StopKind::None;
  switch (cmd) {
    case Command::QuickStop: enter_quick_stop(c, power_lost); return;
    case Command::DisableVoltage:  // transition 9 after the 605Bh stop (L27189-L27211)
    case Command::Shutdown: {      // transition 8 after the 605Bh stop (L27161-L27183)
      const PdsState after = cmd == Command::Shutdown ? PdsState::ReadyToSwitchOn : PdsState::SwitchOnDisabled;
      if (stopping) {
        if (depth(after) < depth(after_stop_)) after_stop_ = after;
      } else {
        const StopKind kind = shutdown_kind(codes_.shutdown(), c.mode, vendor_.present());
        begin_stop(kind, kind == StopKind::DriveSide ? vendor_.servo_off() : DriveSideAction::None, after);
      }
      break;
    }
    case Command::SwitchOn:  // Disable operation: transition 5 after the 605Ch stop (L27308-L27328)
      if (!stopping) {
        const StopKind kind = shutdown_kind(codes_.disable_operation(), c.mode, vendor_.present());
        begin_stop(kind, kind == StopKind::DriveSide ? vendor_.servo_off() : DriveSideAction::None,
                   PdsState::SwitchedOn);
      }
      break;
    case Command::EnableOperation:
    case Command::None:
      break;
  }
  // The state changes once the axis is stopped; it stays OE meanwhile (L27240-L27246).
  if (state_ == PdsState::OperationEnabled && stop_ != StopKind::None && c.stopped) end_stop(after_stop_);
}

void PdsMachine::step_quick_stop_active(Command cmd, const PdsConditions& c) {
  if (c.torque_off) {  // transition 12 (STO, L9735)
    end_stop(PdsState::SwitchOnDisabled);
    return;
  }
  if (!c.main_power) quick_stop_stays_ = false;   // transition 12 on main power off (L9733)
  if (c.stopped) quick_stop_done_ = true;
  if (cmd == Command::EnableOperation && quick_stop_stays_) {  // transition 16 (605Ah 5-7, L9773)
    end_stop(PdsState::OperationEnabled);
    enabled_event_ = true;
    return;
  }
  if (cmd == Command::DisableVoltage) quick_stop_stays_ = false;  // 5-7: Disable voltage after the stop
  // Transition 12: 605Ah 0-3 once the quick stop is done (L9723-L9731).
  if (quick_stop_done_ && !quick_stop_stays_) end_stop(PdsState::SwitchOnDisabled);
}

void PdsMachine::step(std::uint16_t controlword, const PdsConditions& c) {
  stop_started_ = enabled_event_ = fault_reset_event_ = abort_connection_fault_ = false;
  if (state_ == PdsState::NotReadyToSwitchOn) return;  // until power_on()
  codes_.refresh();

  const bool reset_edge = (controlword & cw::fault_reset) && !fault_reset_bit_;
  fault_reset_bit_ = (controlword & cw::fault_reset) != 0;
  const bool power_lost = main_power_ && !c.main_power;
  main_power_ = c.main_power;
  const bool faulting = c.fault && c.fault_reaction != profile::AlarmReaction::None;
  const bool fault_edge = faulting && !faulting_;
  faulting_ = faulting;
  const Command cmd = decode(controlword);

  if (fault_edge && state_ != PdsState::FaultReactionActive && state_ != PdsState::Fault) {
    begin_fault(c);  // transition 13 outranks every command
  }

  switch (state_) {
    case PdsState::NotReadyToSwitchOn:
      break;
    case PdsState::SwitchOnDisabled:
      // Transition 2: Shutdown, not in STO/TO (L9640) and not while the ESM is in Init (L3351).
      if (cmd == Command::Shutdown && !c.torque_off && !c.esm_init) state_ = PdsState::ReadyToSwitchOn;
      break;
    case PdsState::ReadyToSwitchOn:
      if (c.torque_off || c.esm_init || cmd == Command::DisableVoltage || cmd == Command::QuickStop) {
        state_ = PdsState::SwitchOnDisabled;  // transition 7
      } else if ((cmd == Command::SwitchOn || cmd == Command::EnableOperation) && c.main_power) {
        state_ = PdsState::SwitchedOn;  // transition 3 needs main power (L9432-L9434)
        if (cmd == Command::EnableOperation) {  // "Switch on + Enable operation": 3 then 4 (L9849ff, *1)
          state_ = PdsState::OperationEnabled;
          enabled_event_ = true;
        }
      }
      break;
    case PdsState::SwitchedOn:
      if (c.torque_off || c.esm_init || cmd == Command::DisableVoltage || cmd == Command::QuickStop) {
        state_ = PdsState::SwitchOnDisabled;  // transition 10
      } else if (cmd == Command::Shutdown || !c.main_power) {
        state_ = PdsState::ReadyToSwitchOn;  // transition 6 (also main power off detected, L9655)
      } else if (cmd == Command::EnableOperation) {
        state_ = PdsState::OperationEnabled;  // transition 4: set-points cleared by the engine
        enabled_event_ = true;
      }
      break;
    case PdsState::OperationEnabled:
      step_enabled(cmd, c, power_lost);
      break;
    case PdsState::QuickStopActive:
      step_quick_stop_active(cmd, c);
      break;
    case PdsState::FaultReactionActive: {
      if (c.torque_off) set_stop(StopKind::Coast, DriveSideAction::None);  // STO cuts the power stage
      // A newer alarm whose stop lets the motor go takes over (priority L26482-L26508).
      if (faulting && !fault_edge) {
        DriveSideAction action;
        const StopKind kind = fault_stop(c, action);
        if (stop_frees_motor(kind, action) && !stop_frees_motor(stop_, action_)) set_stop(kind, action);
      }
      if (c.stopped) end_stop(PdsState::Fault);  // transition 14 (L27612-L27614)
      break;
    }
    case PdsState::Fault:
      // Transition 15 on the 0->1 edge of bit 7, once the causes are gone (L9761-L9763).
      if (reset_edge && c.fault_reset_allowed) {
        state_ = PdsState::SwitchOnDisabled;
        fault_reset_event_ = true;
      } else if (c.cleared_by_drive && !c.fault) {
        state_ = PdsState::SwitchOnDisabled;   // cleared from the drive's side (DS5C1 L7400-L7402)
      }
      break;
  }
}

}  // namespace vdrive::drive
