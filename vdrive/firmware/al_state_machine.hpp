#pragma once
// The EtherCAT state machine (ESM) of ETG.1000.6 as the three drives implement it: which AL
// Control requests are valid, which AL status code each failure reports, in which state the slave
// is left, and how the error flag is acknowledged. See docs/state-machine.md for the table and
// the manual references.
//
// The machine knows no registers: the firmware feeds it decoded AL Control writes and gives it
// the per-transition checks (mailbox SyncManagers, later PDO/sync) through TransitionHooks; it then
// publishes status_register()/status_code_register() over the PDI. Requests are applied
// synchronously; a real drive takes milliseconds (the master polls AL status, so it cannot tell).
// No allocation, no locks.
#include <cstdint>

#include "ethercat/al_state.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware {

// Outcome of a transition check: code 0 = pass; otherwise the AL status code to report and the
// state the slave falls back to (e.g. a bad mailbox configuration leaves it in Init).
struct CheckResult {
  std::uint16_t code = 0;
  ecat::AlState fallback = ecat::AlState::Init;

  static CheckResult pass() { return {}; }
  bool ok() const { return code == 0; }
};

// What the firmware does around a transition. Checks run before an upward transition is taken;
// entered() runs after the state changed (start/stop mailbox, inputs, outputs).
class TransitionHooks {
public:
  virtual ~TransitionHooks() = default;
  virtual CheckResult check_init_to_preop() = 0;
  virtual CheckResult check_init_to_boot() = 0;
  virtual CheckResult check_preop_to_safeop() = 0;
  virtual CheckResult check_safeop_to_op() = 0;
  virtual void entered(ecat::AlState from, ecat::AlState to) = 0;
};

// The product facts the ESM needs.
struct EsmTraits {
  profile::AlStatusCodes codes;
  bool has_bootstrap = false;
  bool explicit_device_id = false;

  static EsmTraits of(const profile::ProductProfile& p) {
    return EsmTraits{p.al_codes, p.has_bootstrap, p.explicit_device_id};
  }
};

class AlStateMachine {
public:
  explicit AlStateMachine(const EsmTraits& traits) : traits_(traits) {}

  // Power-on state: Init, no error, no ID loaded.
  void reset();

  // Applies one AL Control write. `device_id` is what an ID request shows in AL status code
  // (read by the firmware when the request arrives).
  void on_al_control(ecat::AlControl control, std::uint16_t device_id, TransitionHooks& hooks);

  // A failure the slave detects on its own (e.g. mailbox SMs changed while running): fall to
  // `state` with the error flag and `code`, as the product's manual prescribes.
  // `clearable` false: the error stays until power-on (reset()); the master's acknowledge and every
  // request are ignored while it is pending (A6B Err85.3, "不可清零", L33756).
  void raise(ecat::AlState state, std::uint16_t code, TransitionHooks& hooks, bool clearable = true);

  ecat::AlState state() const { return state_; }
  bool error() const { return error_; }
  std::uint16_t error_code() const { return error_code_; }
  bool error_clearable() const { return !latched_; }
  bool id_loaded() const { return id_loaded_; }

  // Values for AL Status (0x0130) and AL Status Code (0x0134). While the error flag is set the
  // code register shows the error even if an ID is loaded (A6B L5802-L5924).
  std::uint16_t status_register() const {
    return ecat::AlStatusBits::encode(state_, error_, id_loaded_);
  }
  std::uint16_t status_code_register() const {
    if (error_) return error_code_;
    return id_loaded_ ? device_id_ : 0;
  }

private:
  void apply_request(ecat::AlState target, TransitionHooks& hooks);
  void step_up(CheckResult result, ecat::AlState target, TransitionHooks& hooks);
  // Refused request: error flag with `code`; the state stays, except that Op falls to SafeOp
  // (A6B Err80.0/80.1 L32966-L33037, DS5C1 E-801 L7114, ETG.1000.6).
  void refuse(std::uint16_t code, TransitionHooks& hooks);
  void go(ecat::AlState to, TransitionHooks& hooks);

  EsmTraits traits_;
  ecat::AlState state_ = ecat::AlState::Init;
  bool error_ = false;
  std::uint16_t error_code_ = 0;
  bool id_loaded_ = false;
  std::uint16_t device_id_ = 0;
  bool latched_ = false;   // a non-clearable error is pending
};

}  // namespace vdrive::firmware
