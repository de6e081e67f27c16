#include "vdrive/firmware/slave_firmware.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>
#include <memory>

#include "vdrive/drive/product_plant.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/drive/drive_module.hpp"
#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/mailbox/mailbox_module.hpp"
#include "vdrive/firmware/mailbox_sm_check.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/firmware/pdo/process_data_module.hpp"
#include "vdrive/firmware/sync/sync_module.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/od/object_store.hpp"
#include "ethercat/sii.hpp"

namespace vdrive::firmware {

namespace {
// AL events the state machine itself services; modules add theirs. Everything else stays masked
// so it does not raise the IRQ.
constexpr std::uint32_t kEsmEvents = al_event::kAlControl | al_event::kSmActivation;
}  // namespace

struct SlaveFirmware::Impl final : TransitionHooks {
  Impl(const profile::ProductProfile& p, esc::Esc& e, const FirmwareOptions& options)
      : profile(p),
        dictionary(options.dictionary ? options.dictionary : od::shared_dictionary(p, options.profile_dir)),
        objects(*dictionary),
        rules(p.mailbox_rules),
        codes(p.al_codes),
        pdi(e),
        esm(EsmTraits::of(p)),
        boot_rules(boot_mailbox_rules(p)),
        sm_count(std::clamp<int>(p.esc.sm_count, 2, kMaxSyncManagers)) {}

  // A copy: the firmware must not depend on the caller keeping the profile alive.
  profile::ProductProfile profile;
  std::shared_ptr<const od::Dictionary> dictionary;
  od::ObjectStore objects;
  profile::MailboxSmRules rules;
  profile::AlStatusCodes codes;
  Pdi pdi;
  AlStateMachine esm;
  profile::MailboxSmRules boot_rules;
  int sm_count;
  bool mailbox_running = false;
  std::optional<std::uint16_t> device_id_switch;
  std::array<SmChannel, kMaxSyncManagers> sms{};  // scratch for SM reads; no allocation
  SdoAbortRecord sdo_aborts;
  FirmwareContext context{profile, pdi, objects, esm, &sdo_aborts};
  std::vector<std::unique_ptr<FirmwareModule>> modules;  // filled by install_modules()

  // The firmware's parts, in service order. Each issue's module is added here.
  void install_modules(const FirmwareOptions& options) {
    auto mailbox_module = std::make_unique<mailbox::MailboxModule>(context);
    mailbox::MailboxModule* mbx = mailbox_module.get();
    mailbox_ = mbx;
    modules.push_back(std::move(mailbox_module));
    auto process_data = std::make_unique<pdo::ProcessDataModule>(context);
    auto synchronisation = std::make_unique<sync::SyncModule>(context);
    // In DC mode the cycle runs on SYNC0: outputs are taken over and inputs latched there. In SM2
    // and free-run mode the process-data module exchanges on its own SM2/SM3 events.
    pdo::ProcessDataModule* pd = process_data.get();
    sync::SyncModule* sm = synchronisation.get();
    synchronisation->on_start(
        [pd](sync::SyncMode mode) { pd->set_cycle_by_sync(mode == sync::SyncMode::DcSync0); });
    synchronisation->on_cycle([pd, sm](Nanos now) {
      if (sm->mode() != sync::SyncMode::DcSync0) return;
      pd->exchange_outputs(now);
      pd->produce_inputs(now);
    });
    modules.push_back(std::move(process_data));
    modules.push_back(std::move(synchronisation));
    // The CiA 402 drive, last: its power-on sees the parameters the mailbox module restored.
    if (profile.modes.supported_drive_modes != 0 && !profile.modes.modes.empty()) {
      auto drive = std::make_unique<drive_module::DriveModule>(
          context, options.plant ? *options.plant : drive::default_plant(profile),
          [mbx](const ecat::coe::Emergency& e) { mbx->post_emergency(e); });
      drive_module::DriveModule* d = drive.get();
      pd->set_application([d](Nanos now) { d->after_outputs(now); }, [d](Nanos now) { d->before_inputs(now); });
      pd->on_outputs_mapped([d](const pdo::ResolvedMapping& rx) { d->outputs_mapped(rx); });
      drive_ = d;
      modules.push_back(std::move(drive));
    }
  }
  drive_module::DriveModule* drive_ = nullptr;
  mailbox::MailboxModule* mailbox_ = nullptr;

  std::uint32_t serviced_events() const {
    std::uint32_t events = kEsmEvents;
    for (const auto& m : modules) events |= m->serviced_events();
    return events;
  }

  void power_on() {
    objects.reset_to_defaults();   // RAM values are lost with the control power
    for (auto& m : modules) m->power_on(now_);
    esm.reset();
    mailbox_running = false;
    pdi.write_u32(reg::kAlEventMask, serviced_events());
    // A drive that checks its SII in every state reads it at start-up (A6B Err85.3, L33734-L33766).
    if (profile.sii_check.enabled && profile.sii_check.every_state && !sii_ok(true)) raise_sii_error();
    publish();
  }

  // ---- SII EEPROM check (profile.sii_check) --------------------------------------------------
  // The ESC's EEPROM status (0x0502) shows none of the product's error bits, and, with `identity`,
  // the SII's vendor ID, product code and revision (words 8-13) are 1018h:01-03.
  bool sii_ok(bool with_identity) {
    const profile::SiiCheck& c = profile.sii_check;
    if ((pdi.read_u16(reg::kSiiControlStatus) & c.error_bits) != 0) return false;
    if (!with_identity || !c.identity) return true;
    const od::Dictionary& d = objects.dictionary();
    constexpr std::uint16_t kWords[] = {ecat::sii::kWordVendorId, ecat::sii::kWordProductCode, ecat::sii::kWordRevision};
    for (std::uint8_t sub = 1; sub <= 3; ++sub) {
      const std::uint16_t word = kWords[sub - 1];
      const std::optional<std::uint16_t> low = pdi.eeprom_word(word), high = pdi.eeprom_word(word + 1u);
      if (!low || !high) return false;   // the EEPROM cannot be read: "SII 的读出不正确"
      const od::EntryDesc* e = d.find(0x1018, sub);
      if (e == nullptr) continue;
      const std::uint64_t object = ecat::get_le(std::as_const(objects).raw(*e));
      if (object != (static_cast<std::uint32_t>(*high) << 16 | *low)) return false;
    }
    return true;
  }
  void raise_sii_error() {
    esm.raise(ecat::AlState::Init, codes.eeprom_error, *this, profile.sii_check.clearable);
    publish();
  }
  // In every state: the error bits whenever the firmware runs (once raised, nothing more to see).
  void watch_sii() {
    if (!profile.sii_check.every_state || (esm.error() && !esm.error_clearable())) return;
    if (!sii_ok(false)) raise_sii_error();
  }

  void on_irq(Nanos now) {
    watch_sii();
    const std::uint32_t events = pdi.read_u32(reg::kAlEventRequest);
    for (auto& m : modules) {
      m->on_events(events, now);
      apply_fault(*m);
    }
    if (events & al_event::kAlControl) {
      // Reading AL Control clears the event in the ESC.
      const ecat::AlControl control = ecat::AlControl::decode(pdi.read_u16(reg::kAlControl));
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
    const bool boot = esm.state() == ecat::AlState::Boot;
    if (check_mailbox_sms(channels, boot ? boot_rules : rules) == MailboxSmFault::Ok) return;
    const std::uint16_t code =
        boot ? codes.invalid_boot_mailbox_config : codes.invalid_mailbox_config;
    esm.raise(ecat::AlState::Init, code, *this);
    publish();
  }

  std::span<const SmChannel> read_sms() {
    for (int n = 0; n < sm_count; ++n) sms[static_cast<std::size_t>(n)] = pdi.read_sm(n);
    return std::span<const SmChannel>(sms.data(), static_cast<std::size_t>(sm_count));
  }

  // A module detected a failure on its own (watchdog, lost sync): fall back as it asks.
  void apply_fault(FirmwareModule& m) {
    FirmwareModule::Fault fault;
    if (!m.take_fault(fault)) return;
    esm.raise(fault.state, fault.code, *this);
    publish();
  }

  void tick(Nanos now) {
    watch_sii();
    for (auto& m : modules) {
      if (m->next_deadline() <= now) m->tick(now);
      apply_fault(*m);
    }
  }

  Nanos next_deadline() const {
    Nanos next = std::numeric_limits<Nanos>::max();
    for (const auto& m : modules) next = std::min(next, m->next_deadline());
    return next;
  }

  // Code first, then status: a master that sees the error flag finds the code already there.
  void publish() {
    pdi.write_u16(reg::kAlStatusCode, esm.status_code_register());
    pdi.write_u16(reg::kAlStatus, esm.status_register());
  }

  // ---- TransitionHooks ----------------------------------------------------------------------
  CheckResult check_init_to_preop() override {
    // ETG slave stack code: the EEPROM was not loaded -> 0x0051, the slave stays in Init.
    if (profile.sii_check.enabled && !profile.sii_check.every_state && !sii_ok(false))
      return {codes.eeprom_error, ecat::AlState::Init};
    if (!profile.has_mailbox()) return CheckResult::pass();  // nothing to check (simple I/O)
    if (check_mailbox_sms(read_sms(), rules) != MailboxSmFault::Ok)
      return {codes.invalid_mailbox_config, ecat::AlState::Init};
    return CheckResult::pass();
  }
  CheckResult check_init_to_boot() override {
    if (check_mailbox_sms(read_sms(), boot_rules) != MailboxSmFault::Ok)
      return {codes.invalid_boot_mailbox_config, ecat::AlState::Init};
    return CheckResult::pass();
  }
  // The modules check what they own: SM2/SM3 and PDO sizes, sync mode and cycle time, DC
  // activation, watchdog, PLL lock (PreOp->SafeOp); outputs valid (SafeOp->Op).
  CheckResult check_modules(ecat::AlState from, ecat::AlState to) {
    for (auto& m : modules) {
      const CheckResult r = m->check_transition(from, to);
      if (!r.ok()) return r;
    }
    return CheckResult::pass();
  }
  CheckResult check_preop_to_safeop() override { return check_modules(ecat::AlState::PreOp, ecat::AlState::SafeOp); }
  CheckResult check_safeop_to_op() override { return check_modules(ecat::AlState::SafeOp, ecat::AlState::Op); }

  void entered(ecat::AlState from, ecat::AlState to) override {
    // The mailbox runs in PreOp, SafeOp, Op and Boot. Going to Init stops it and forgets its
    // state; the ESC's SyncManagers are left as they are (the master reconfigures them).
    mailbox_running = profile.has_mailbox() && to != ecat::AlState::Init;
    for (auto& m : modules) m->entered(from, to, now_);
  }
  Nanos now_ = 0;  // time of the event being serviced, for entered()
};

SlaveFirmware::SlaveFirmware(const profile::ProductProfile& profile, esc::Esc& esc, const FirmwareOptions& options)
    : impl_(std::make_unique<Impl>(profile, esc, options)) {
  impl_->install_modules(options);
}

SlaveFirmware::~SlaveFirmware() = default;

void SlaveFirmware::power_on(Nanos now) {
  impl_->now_ = now;
  impl_->power_on();
}

void SlaveFirmware::on_irq(Nanos now) {
  impl_->now_ = now;
  impl_->on_irq(now);
}

void SlaveFirmware::tick(Nanos now) {
  impl_->now_ = now;
  impl_->tick(now);
}

Nanos SlaveFirmware::next_deadline() const { return impl_->next_deadline(); }

void SlaveFirmware::set_control_step_batch(Nanos wait) {
  if (impl_->drive_ != nullptr) impl_->drive_->set_step_batch(wait);
}

Nanos SlaveFirmware::next_control_step() const {
  return impl_->drive_ != nullptr ? impl_->drive_->engine().next_step() : std::numeric_limits<Nanos>::max();
}

bool SlaveFirmware::step_once(Nanos now) {
  impl_->now_ = now;
  if (impl_->drive_ == nullptr) return false;
  const bool ran = impl_->drive_->step_once(now);
  impl_->apply_fault(*impl_->drive_);
  return ran;
}

void SlaveFirmware::set_device_id_switch(std::uint16_t id) { impl_->device_id_switch = id; }

drive::DriveEngine* SlaveFirmware::drive() { return impl_->drive_ ? &impl_->drive_->engine() : nullptr; }
plant::Plant* SlaveFirmware::plant() { return impl_->drive_ ? &impl_->drive_->plant() : nullptr; }
mailbox::MailboxModule& SlaveFirmware::mailbox() { return *impl_->mailbox_; }
const SdoAbortRecord& SlaveFirmware::sdo_aborts() const { return impl_->sdo_aborts; }

od::ObjectStore& SlaveFirmware::objects() { return impl_->objects; }

}  // namespace vdrive::firmware
