#include "vdrive/firmware/slave_firmware.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <span>

#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/mailbox_sm_check.hpp"
#include "vdrive/firmware/pdi.hpp"

namespace vdrive::firmware {

namespace {
// AL events this firmware services; everything else stays masked so it does not raise the IRQ.
// Later issues add the mailbox (SM0/SM1) and process-data (SM2, SYNC0) events.
constexpr std::uint32_t kServicedEvents = al_event::kAlControl | al_event::kSmActivation;
}  // namespace

struct SlaveFirmware::Impl final : TransitionHooks {
  Impl(const profile::ProductProfile& p, esc::Esc& e)
      : rules(p.mailbox_rules),
        codes(p.al_codes),
        pdi(e),
        esm(EsmTraits::of(p)),
        boot_rules(boot_mailbox_rules(p)),
        sm_count(std::clamp<int>(p.esc.sm_count, 2, kMaxSyncManagers)) {}

  // Copies, not a reference: the firmware must not depend on the caller keeping the profile alive.
  profile::MailboxSmRules rules;
  profile::AlStatusCodes codes;
  Pdi pdi;
  AlStateMachine esm;
  profile::MailboxSmRules boot_rules;
  int sm_count;
  bool mailbox_running = false;
  std::optional<std::uint16_t> device_id_switch;
  std::array<SmChannel, kMaxSyncManagers> sms{};  // scratch for SM reads; no allocation

  void power_on() {
    esm.reset();
    mailbox_running = false;
    pdi.write_u32(reg::kAlEventMask, kServicedEvents);
    publish();
  }

  void on_irq() {
    const std::uint32_t events = pdi.read_u32(reg::kAlEventRequest);
    if (events & al_event::kAlControl) {
      // Reading AL Control clears the event in the ESC.
      const AlControl control = AlControl::decode(pdi.read_u16(reg::kAlControl));
      const std::uint16_t device_id = control.id_request ? device_id_for_request() : 0;
      esm.on_al_control(control, device_id, *this);
      publish();
    }
    if (events & al_event::kSmActivation) on_sm_changed();
  }

  std::uint16_t device_id_for_request() {
    return device_id_switch ? *device_id_switch : pdi.read_u16(reg::kStationAlias);
  }

  // The master changed an SM activation. Reading the SM channels clears the event. While the
  // mailbox runs, a now-invalid mailbox configuration drops the slave to Init (A6B Err81.1 is
  // detected in PreOp, SafeOp, Op and Boot, L33400-L33446).
  void on_sm_changed() {
    const std::span<const SmChannel> channels = read_sms();
    if (!mailbox_running) return;
    const bool boot = esm.state() == AlState::Boot;
    if (check_mailbox_sms(channels, boot ? boot_rules : rules) == MailboxSmFault::Ok) return;
    const std::uint16_t code =
        boot ? codes.invalid_boot_mailbox_config : codes.invalid_mailbox_config;
    esm.raise(AlState::Init, code, *this);
    publish();
  }

  std::span<const SmChannel> read_sms() {
    for (int n = 0; n < sm_count; ++n) sms[static_cast<std::size_t>(n)] = pdi.read_sm(n);
    return std::span<const SmChannel>(sms.data(), static_cast<std::size_t>(sm_count));
  }

  // Code first, then status: a master that sees the error flag finds the code already there.
  void publish() {
    pdi.write_u16(reg::kAlStatusCode, esm.status_code_register());
    pdi.write_u16(reg::kAlStatus, esm.status_register());
  }

  // ---- TransitionHooks ----------------------------------------------------------------------
  CheckResult check_init_to_preop() override {
    if (check_mailbox_sms(read_sms(), rules) != MailboxSmFault::Ok)
      return {codes.invalid_mailbox_config, AlState::Init};
    return CheckResult::pass();
  }
  CheckResult check_init_to_boot() override {
    if (check_mailbox_sms(read_sms(), boot_rules) != MailboxSmFault::Ok)
      return {codes.invalid_boot_mailbox_config, AlState::Init};
    return CheckResult::pass();
  }
  // Issue 4 adds here: SM2/SM3 settings (0x001D/0x001E), PDO sizes (0x0024/0x0025), sync mode and
  // cycle time (0x0028/0x0035), DC activation (0x0030), watchdog (0x001F), PLL lock (0x002D).
  // Until then these transitions are accepted unchecked.
  CheckResult check_preop_to_safeop() override { return CheckResult::pass(); }
  // Issue 4: outputs valid / SM2 watchdog armed before Op.
  CheckResult check_safeop_to_op() override { return CheckResult::pass(); }

  void entered(AlState /*from*/, AlState to) override {
    // The mailbox runs in PreOp, SafeOp, Op and Boot. Going to Init stops it and forgets its
    // state; the ESC's SyncManagers are left as they are (the master reconfigures them).
    mailbox_running = to != AlState::Init;
  }
};

SlaveFirmware::SlaveFirmware(const profile::ProductProfile& profile, esc::Esc& esc)
    : impl_(std::make_unique<Impl>(profile, esc)) {}

SlaveFirmware::~SlaveFirmware() = default;

void SlaveFirmware::power_on(Nanos /*now*/) { impl_->power_on(); }

void SlaveFirmware::on_irq(Nanos /*now*/) { impl_->on_irq(); }

void SlaveFirmware::tick(Nanos /*now*/) {}

Nanos SlaveFirmware::next_deadline() const { return std::numeric_limits<Nanos>::max(); }

void SlaveFirmware::set_device_id_switch(std::uint16_t id) { impl_->device_id_switch = id; }

}  // namespace vdrive::firmware
