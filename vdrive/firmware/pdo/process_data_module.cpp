#include "vdrive/firmware/pdo/process_data_module.hpp"

#include <algorithm>
#include <limits>
#include <span>

#include "ethercat/al_status_code.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/firmware/pdo/pdo_assignment_rules.hpp"
#include "vdrive/firmware/pdo/pdo_write_rules.hpp"
#include "vdrive/firmware/pdo/process_data_sm_check.hpp"
#include "vdrive/firmware/pdo/watchdog_setting_check.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::firmware::pdo {

namespace {

// The sync module owns the DC rules; the watchdog check only needs to know whether the slave
// runs on SYNC0 (cyclic unit and SYNC0 both activated).
constexpr std::uint8_t kDcSync0Active = reg::dc_activation::kCyclicOperation | reg::dc_activation::kSync0;

// ETG.1000.6 codes, used when a product names none for a situation.
namespace code = ecat::al_status_code;
constexpr std::uint16_t kEtgWatchdog = code::kSyncManagerWatchdog, kEtgOutputConfig = code::kInvalidOutputConfig,
                        kEtgInputConfig = code::kInvalidInputConfig, kEtgWatchdogConfig = code::kInvalidWatchdogConfig,
                        kEtgInputMapping = code::kInvalidInputMapping, kEtgOutputMapping = code::kInvalidOutputMapping;

}  // namespace

ProcessDataModule::ProcessDataModule(FirmwareContext& context)
    : ctx_(context),
      limits_(limits_for(context.profile)),
      watchdog_limits_(watchdog_limits_for(context.profile)),
      codes_(context.profile.al_codes),
      ram_end_(reg::kRegisterEnd + 1024u * context.profile.esc.ram_kib),
      sm_count_(std::clamp<int>(context.profile.esc.sm_count, 0, kMaxSyncManagers)),
      // SM2/SM3 on a device with a mailbox; simple I/O devices use SM0/SM1 (ESI, SII SM category).
      outputs_sm_(std::clamp(context.profile.process_data_sm(profile::SyncManagerSpec::Kind::Outputs, kOutputsSm), 0,
                             std::max(sm_count_ - 1, 0))),
      inputs_sm_(std::clamp(context.profile.process_data_sm(profile::SyncManagerSpec::Kind::Inputs, kInputsSm), 0,
                            std::max(sm_count_ - 1, 0))),
      outputs_event_(1u << (al_event::kSmShift + outputs_sm_)),
      inputs_event_(1u << (al_event::kSmShift + inputs_sm_)),
      mode_checked_(context.profile.pdo_rules.sm_control_mode_checked),
      unused_disabled_(context.profile.pdo_rules.unused_sm_must_be_disabled) {
  install_pdo_write_rules(ctx_.objects, ctx_.esm, limits_);
}

void ProcessDataModule::power_on(Nanos /*now*/) {
  running_ = false;
  polling_ = false;
  outputs_valid_ = false;
  new_outputs_ = false;
  cycle_by_sync_ = false;
  rx_plan_.clear();
  tx_plan_.clear();
}

// Without an AL event for its process-data SyncManagers (control byte bit 5 clear, as on simple
// I/O such as a digital output terminal) the firmware cannot wait for the master's frame: it looks
// at the buffers every kPollPeriod, takes new outputs and refreshes the inputs.
Nanos ProcessDataModule::next_deadline() const {
  return running_ && polling_ && !cycle_by_sync_ ? poll_at_ : std::numeric_limits<Nanos>::max();
}

void ProcessDataModule::tick(Nanos now) {
  if (!running_ || !polling_ || cycle_by_sync_ || now < poll_at_) return;
  poll_at_ = now + kPollPeriod;
  const std::uint8_t status = ctx_.pdi.read_u8(sm_register(outputs_sm_, reg::sm::kStatus));
  if (rx_plan_.bytes() > 0 && (status & reg::sm::kIrqWrite) != 0) exchange_outputs(now);
  produce_inputs(now);
}

std::uint32_t ProcessDataModule::serviced_events() const {
  return outputs_event_ | inputs_event_ | al_event::kPdWatchdog | al_event::kSmActivation;
}

void ProcessDataModule::on_events(std::uint32_t events, Nanos now) {
  if (events & al_event::kPdWatchdog) on_watchdog();
  if ((events & al_event::kSmActivation) && running_) check_sms_while_running();
  if (!running_) return;
  if (events & outputs_event_) {
    if (cycle_by_sync_) {
      read_outputs();  // release the buffer; the objects are updated at SYNC0
      new_outputs_ = true;
    } else {
      exchange_outputs(now);
      produce_inputs(now);
    }
  }
  if ((events & inputs_event_) && tx_plan_.bytes() > 0) {
    if (cycle_by_sync_) {
      write_inputs();  // hand out the inputs latched at the last sync point again
    } else {
      produce_inputs(now);
    }
  }
}

// ---- cyclic path -----------------------------------------------------------------------------

void ProcessDataModule::read_outputs() {
  const std::uint16_t n = rx_plan_.bytes();
  if (n == 0) return;
  ctx_.pdi.read(sm2_start_, std::span<std::uint8_t>(rx_image_.data(), n));
}

void ProcessDataModule::write_inputs() {
  const std::uint16_t n = tx_plan_.bytes();
  if (n == 0) return;
  ctx_.pdi.write(sm3_start_, std::span<const std::uint8_t>(tx_image_.data(), n));
}

void ProcessDataModule::exchange_outputs(Nanos now) {
  if (!running_) return;
  // At SYNC0, did the master write outputs since the last pulse? Known from the SM2 event, or
  // (its AL event not enabled in the SM2 control byte) from the buffer's write flag, which the
  // read below clears. A pulse with none is a lost set-point: the application is not told of new
  // outputs, so the cyclic modes bridge it (A6B command compensation, L16880-L16917) instead of
  // taking the old target again as if the axis were to stand still for a cycle.
  bool fresh = true;
  if (cycle_by_sync_) {
    const std::uint8_t status = ctx_.pdi.read_u8(sm_register(outputs_sm_, reg::sm::kStatus));
    fresh = new_outputs_ || (status & reg::sm::kIrqWrite) != 0;
    new_outputs_ = false;
  }
  read_outputs();
  if (ctx_.esm.state() != ecat::AlState::Op || rx_plan_.bytes() == 0) return;
  rx_plan_.scatter(std::span<const std::uint8_t>(rx_image_.data(), rx_plan_.bytes()));
  outputs_valid_ = true;
  if (after_outputs_ && fresh) after_outputs_(now);
}

void ProcessDataModule::produce_inputs(Nanos now) {
  if (!running_ || tx_plan_.bytes() == 0) return;
  if (before_inputs_) before_inputs_(now);
  tx_plan_.gather(std::span<std::uint8_t>(tx_image_.data(), tx_plan_.bytes()));
  write_inputs();
}

// A6B Err80.4 (L33098-L33134), DS5C1 E-804 (L7117): the SM2 watchdog expired -> SafeOp with
// AL 001Bh. Only Op uses the outputs, so only Op reacts (A6B: "effectively Op-only", L33132).
// Reading 0440h clears the event; the master recovers with Error Ind Ack and a new Op request.
void ProcessDataModule::on_watchdog() {
  const std::uint8_t status = ctx_.pdi.read_u8(reg::kWatchdogStatusProcessData);
  if ((status & 0x01) != 0) return;  // running again: retriggered before we looked
  if (ctx_.esm.state() != ecat::AlState::Op) return;
  outputs_valid_ = false;
  raise_fault(code_or(codes_.sync_watchdog, kEtgWatchdog), ecat::AlState::SafeOp);
}

// A6B Err81.7 is also detected in SafeOp and Op (L33546-L33624): the master changed SM2/SM3.
void ProcessDataModule::check_sms_while_running() {
  for (int n = 0; n < sm_count_; ++n) sms_[static_cast<std::size_t>(n)] = ctx_.pdi.read_sm(n);
  const std::span<const SmChannel> sms(sms_.data(), static_cast<std::size_t>(sm_count_));
  if (check_process_data_sm(sms, outputs_sm_, true, rx_plan_.bytes(), ram_end_, mode_checked_, unused_disabled_) != PdSmFault::Ok) {
    raise_fault(code_or(codes_.invalid_output_config, kEtgOutputConfig), ecat::AlState::PreOp);
  } else if (check_process_data_sm(sms, inputs_sm_, false, tx_plan_.bytes(), ram_end_, mode_checked_, unused_disabled_) != PdSmFault::Ok) {
    raise_fault(code_or(codes_.invalid_input_config, kEtgInputConfig), ecat::AlState::PreOp);
  }
}

// ---- transitions -----------------------------------------------------------------------------

CheckResult ProcessDataModule::check_transition(ecat::AlState from, ecat::AlState to) {
  if (from == ecat::AlState::PreOp && to == ecat::AlState::SafeOp) return check_preop_to_safeop();
  return CheckResult::pass();
}

// Order: mapping (A6B Err85.0/85.1), SyncManagers (Err81.7), watchdog (Err81.4). Every failure
// leaves the slave in PreOp (A6B 8-1 table; DS5C1 E-817/E-85x).
CheckResult ProcessDataModule::check_preop_to_safeop() {
  resolve(ctx_.objects, Direction::Tx, limits_.tx, tx_map_);
  if (!tx_map_.ok()) return {code_or(codes_.invalid_input_mapping, kEtgInputMapping), ecat::AlState::PreOp};
  resolve(ctx_.objects, Direction::Rx, limits_.rx, rx_map_);
  if (!rx_map_.ok()) return {code_or(codes_.invalid_output_mapping, kEtgOutputMapping), ecat::AlState::PreOp};
  // An assignment against the device's ESI rules (a mandatory PDO left out, two excluding PDOs).
  if (check_assignment_rules(ctx_.objects, kTxAssign, ctx_.profile.pdo_rules.tx_objects) != AssignmentFault::Ok)
    return {code_or(codes_.invalid_input_mapping, kEtgInputMapping), ecat::AlState::PreOp};
  if (check_assignment_rules(ctx_.objects, kRxAssign, ctx_.profile.pdo_rules.rx_objects) != AssignmentFault::Ok)
    return {code_or(codes_.invalid_output_mapping, kEtgOutputMapping), ecat::AlState::PreOp};

  for (int n = 0; n < sm_count_; ++n) sms_[static_cast<std::size_t>(n)] = ctx_.pdi.read_sm(n);
  const std::span<const SmChannel> sms(sms_.data(), static_cast<std::size_t>(sm_count_));
  if (check_process_data_sm(sms, outputs_sm_, true, rx_map_.bytes(), ram_end_, mode_checked_, unused_disabled_) != PdSmFault::Ok) {
    return {code_or(codes_.invalid_output_config, kEtgOutputConfig), ecat::AlState::PreOp};
  }
  if (check_process_data_sm(sms, inputs_sm_, false, tx_map_.bytes(), ram_end_, mode_checked_, unused_disabled_) != PdSmFault::Ok) {
    return {code_or(codes_.invalid_input_config, kEtgInputConfig), ecat::AlState::PreOp};
  }

  WatchdogSetting wd;
  const std::uint16_t wd_time = ctx_.pdi.read_u16(reg::kWatchdogTimeProcessData);
  wd.enabled = rx_map_.bytes() > 0 && wd_time != 0 &&
               (sms[static_cast<std::size_t>(outputs_sm_)].control & reg::sm::kWatchdogTrigger) != 0;
  wd.time = process_data_watchdog_time(ctx_.pdi.read_u16(reg::kWatchdogDivider), wd_time);
  const bool dc = (ctx_.pdi.read_u8(reg::kDcActivation) & kDcSync0Active) == kDcSync0Active;
  wd.synchronised = dc || read_unsigned(ctx_.objects, kSm2Sync, 1) != 0;
  wd.cycle_ns = read_unsigned(ctx_.objects, kSm2Sync, 2);
  if (!watchdog_setting_ok(wd, watchdog_limits_)) {
    return {code_or(codes_.invalid_watchdog_config, kEtgWatchdogConfig), ecat::AlState::PreOp};
  }
  return CheckResult::pass();
}

void ProcessDataModule::entered(ecat::AlState from, ecat::AlState to, Nanos now) {
  if (from == ecat::AlState::PreOp && to == ecat::AlState::SafeOp) {
    // The mapping becomes effective here (A6B L7008, L7172, L7311).
    rx_plan_.build(ctx_.objects, rx_map_);
    tx_plan_.build(ctx_.objects, tx_map_);
    if (outputs_mapped_) outputs_mapped_(rx_map_);
    sm2_start_ = sms_[static_cast<std::size_t>(outputs_sm_)].start;
    sm3_start_ = sms_[static_cast<std::size_t>(inputs_sm_)].start;
    const auto event_enabled = [&](int sm, std::uint16_t bytes) {
      return bytes == 0 || (sms_[static_cast<std::size_t>(sm)].control & reg::sm::kAlEventEnable) != 0;
    };
    polling_ = !event_enabled(outputs_sm_, rx_plan_.bytes()) ||
               (rx_plan_.bytes() == 0 && tx_plan_.bytes() > 0 && !event_enabled(inputs_sm_, 0xFFFF));
    poll_at_ = now + kPollPeriod;
    running_ = true;
    outputs_valid_ = false;
    produce_inputs(now);  // TxPDO valid from SafeOp on (A6B L7619-L7621)
    return;
  }
  if (to == ecat::AlState::Op) return;
  outputs_valid_ = false;
  if (rank(to) < rank(ecat::AlState::SafeOp)) {
    running_ = false;
    cycle_by_sync_ = false;
    rx_plan_.clear();
    tx_plan_.clear();
  }
}

}  // namespace vdrive::firmware::pdo
