#include "vdrive/firmware/al_state_machine.hpp"

namespace vdrive::firmware {

void AlStateMachine::reset() {
  state_ = ecat::AlState::Init;
  error_ = false;
  error_code_ = 0;
  id_loaded_ = false;
  device_id_ = 0;
  latched_ = false;
}

void AlStateMachine::on_al_control(ecat::AlControl control, std::uint16_t device_id,
                                   TransitionHooks& hooks) {
  // Explicit Device ID follows bit5 of every AL Control write; products without it ignore the
  // bit (DS5C1: "not supported", L2335).
  if (traits_.explicit_device_id) {
    id_loaded_ = control.id_request;
    device_id_ = control.id_request ? device_id : 0;
  }

  // A non-clearable error: the slave stays where it fell, flag and code stay, whatever is asked.
  if (latched_) return;

  const bool wants_init = control.requested == static_cast<std::uint8_t>(ecat::AlState::Init);
  if (error_) {
    // ETG.1000.6 / ETG SSC: with the error flag set, a request without Error Ind Ack is ignored
    // (state and code stay), except a request for Init, which is always honoured.
    if (!control.error_ack && !wants_init) return;
    error_ = false;
    error_code_ = 0;
  }

  if (!ecat::is_defined_state(control.requested)) {
    refuse(traits_.codes.unknown_state, hooks);
    return;
  }
  apply_request(static_cast<ecat::AlState>(control.requested), hooks);
}

void AlStateMachine::apply_request(ecat::AlState target, TransitionHooks& hooks) {
  const ecat::AlState from = state_;

  // Bootstrap hangs off Init only: IB and BI are its only transitions (A6B diagram L3287-L3317;
  // Err80.0 lists PB, SB, OB, BB, BP, BS, BO as invalid, L32966-L33006).
  if (target == ecat::AlState::Boot) {
    if (from != ecat::AlState::Init) {
      refuse(traits_.codes.invalid_transition, hooks);
    } else if (!traits_.has_bootstrap) {
      // A6B Err80.2 / DS5C1 E-802: 0x0013, slave stays in Init (L33038-L33062, L7115).
      error_ = true;
      error_code_ = traits_.codes.bootstrap_not_supported;
    } else {
      step_up(hooks.check_init_to_boot(), target, hooks);
    }
    return;
  }
  if (from == ecat::AlState::Boot) {
    if (target == ecat::AlState::Init) go(target, hooks);
    else refuse(traits_.codes.invalid_transition, hooks);
    return;
  }

  // The Init < PreOp < SafeOp < Op ladder: down any number of steps, up one step at a time.
  const int up = rank(target) - rank(from);
  if (up == 0) return;  // same state: nothing to do (an acknowledged error is cleared above)
  if (up < 0) {
    go(target, hooks);
    return;
  }
  if (up > 1) {
    refuse(traits_.codes.invalid_transition, hooks);  // IS, IO, PO
    return;
  }
  switch (target) {
    case ecat::AlState::PreOp: step_up(hooks.check_init_to_preop(), target, hooks); break;
    case ecat::AlState::SafeOp: step_up(hooks.check_preop_to_safeop(), target, hooks); break;
    case ecat::AlState::Op: step_up(hooks.check_safeop_to_op(), target, hooks); break;
    default: refuse(traits_.codes.invalid_transition, hooks); break;
  }
}

void AlStateMachine::step_up(CheckResult result, ecat::AlState target, TransitionHooks& hooks) {
  if (result.ok()) {
    go(target, hooks);
    return;
  }
  error_ = true;
  error_code_ = result.code;
  // A failed check never leaves the slave above where it was; it may drop it lower (a bad
  // mailbox found at PreOp->SafeOp sends an A6B to Init, L33400-L33446).
  if (rank(result.fallback) < rank(state_)) go(result.fallback, hooks);
}

void AlStateMachine::refuse(std::uint16_t code, TransitionHooks& hooks) {
  error_ = true;
  error_code_ = code;
  if (state_ == ecat::AlState::Op) go(ecat::AlState::SafeOp, hooks);
}

void AlStateMachine::raise(ecat::AlState state, std::uint16_t code, TransitionHooks& hooks, bool clearable) {
  if (latched_) return;   // the first non-clearable error keeps its code
  error_ = true;
  error_code_ = code;
  latched_ = !clearable;
  go(state, hooks);
}

void AlStateMachine::go(ecat::AlState to, TransitionHooks& hooks) {
  const ecat::AlState from = state_;
  if (from == to) return;
  state_ = to;
  hooks.entered(from, to);
}

}  // namespace vdrive::firmware
