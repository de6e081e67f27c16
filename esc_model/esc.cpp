// Public API of the ESC: construction and power-on reset, EEPROM reload, PDI access, time.
// The datagram engine, memory path, register side effects and data link live in their own
// files (see esc_impl.hpp).
#include "esc_model/esc.hpp"

#include <algorithm>

#include "esc_model/esc_impl.hpp"

namespace vdrive::esc {

namespace {
constexpr std::uint32_t kRegisterAndRamLimit = 0x10000;

EscConfig without_image(const EscConfig& c) {
  EscConfig copy = c;
  copy.sii_image.clear();
  copy.sii_image.shrink_to_fit();
  return copy;
}
}  // namespace

Esc::Impl::Impl(const EscConfig& config, const Clock& c)
    : identity(without_image(config)), clock(c), sii(config.sii_image), dc(c) {
  fmmu_count = std::min<int>(config.fmmu_count, reg::kMaxFmmus);
  sm_count = std::min<int>(config.sm_count, reg::kMaxSyncManagers);
  ram_end = std::min<std::uint32_t>(reg::kRegisterEnd + config.ram_kib * 1024u,
                                    kRegisterAndRamLimit);
  build_permissions();
}

void Esc::Impl::build_permissions() {
  permissions.fill(0);
  auto allow = [this](std::uint16_t first, std::uint16_t count, std::uint8_t who) {
    for (std::uint16_t i = 0; i < count; ++i) permissions[first + i] = who;
  };
  constexpr std::uint8_t E = kEcatWritable;
  constexpr std::uint8_t P = kPdiWritable;
  allow(reg::kStationAddress, 2, E);
  allow(reg::kStationAlias, 2, P);
  allow(reg::kEscResetEcat, 1, E);
  allow(reg::kDlControl, 4, E);
  allow(reg::kPhysicalRwOffset, 2, E);
  allow(reg::kAlControl, 2, E);
  allow(reg::kAlStatus, 2, P);
  allow(reg::kAlStatusCode, 2, P);
  allow(reg::kLedOverride, 2, E | P);
  allow(reg::kEcatEventMask, 2, E);
  allow(reg::kAlEventMask, 4, P);
  // Error counters: a write by the master clears them (see register_effects.cpp).
  allow(reg::kRxErrorCounter, reg::kPdiErrors + 1 - reg::kRxErrorCounter, E);
  allow(reg::kLostLinkCounter, reg::kLostLinkCounterEnd - reg::kLostLinkCounter, E);
  allow(reg::kWatchdogDivider, 2, E);
  allow(reg::kWatchdogTimePdi, 2, E);
  allow(reg::kWatchdogTimeProcessData, 2, E);
  allow(reg::kWatchdogCounterProcessData, 2, E);
  for (int n = 0; n < fmmu_count; ++n) {
    allow(static_cast<std::uint16_t>(reg::kFmmu0 + reg::kFmmuStride * n), reg::fmmu::kUsedBytes, E);
  }
  for (int n = 0; n < sm_count; ++n) {
    const auto base = static_cast<std::uint16_t>(reg::kSm0 + reg::kSmStride * n);
    allow(base, reg::sm::kStatus, E);  // start, length, control: only while disabled
    allow(base + reg::sm::kActivate, 1, E);
    allow(base + reg::sm::kPdiControl, 1, P);
  }
  allow(reg::kUserRam, reg::kRegisterEnd - reg::kUserRam, E | P);
}

void Esc::Impl::load_register_defaults() {
  mem.fill(0);
  mem[reg::kType] = identity.type;
  mem[reg::kRevision] = identity.revision;
  put16(reg::kBuild, identity.build);
  mem[reg::kFmmusSupported] = static_cast<std::uint8_t>(fmmu_count);
  mem[reg::kSyncManagersSupported] = static_cast<std::uint8_t>(sm_count);
  mem[reg::kRamSize] = identity.ram_kib;
  mem[reg::kPortDescriptor] = identity.port_descriptor;
  put16(reg::kFeatures, identity.features);
  put32(reg::kDlControl, reg::dl_control::kResetValue);
  put16(reg::kAlControl, reg::kAlStateInit);
  put16(reg::kAlStatus, reg::kAlStateInit);
  put32(reg::kAlEventMask, reg::kAlEventMaskReset);
  put16(reg::kWatchdogDivider, reg::kWatchdogDividerReset);
  put16(reg::kWatchdogTimePdi, reg::kWatchdogTimeReset);
  put16(reg::kWatchdogTimeProcessData, reg::kWatchdogTimeReset);
}

void Esc::Impl::power_on_reset() {
  load_register_defaults();
  for (int n = 0; n < reg::kMaxSyncManagers; ++n) {
    sms[static_cast<std::size_t>(n)] = SyncManager{};
  }
  fmmus.fill(Fmmu{});
  pd_watchdog.reset();
  pdi_watchdog.reset();
  configure_watchdogs();
  auto_closed.fill(false);
  pdi_operational = false;
  pdi_watchdog_ok = false;
  reset_progress = 0;
  reset_pending = false;
  access_now = clock.now();
  sii.reset();
  dc.reset();
  apply_eeprom_reload();
  update_dl_status();
  set_ecat_event(reg::ecat_event::kDlStatus, false);  // power-on state is not a change
}

void Esc::Impl::apply_eeprom_reload() {
  if (!sii.take_reload_done()) return;
  put16(reg::kPdiControl, sii.word(reg::kEepromPdiControlWord));
  put16(reg::kPdiConfiguration, sii.word(reg::kEepromPdiConfigWord));
  put16(reg::kExtendedPdiConfiguration, sii.word(reg::kEepromExtPdiConfigWord));
  put16(reg::kStationAlias, sii.word(reg::kEepromAliasWord));
  const std::uint16_t pulse = sii.word(reg::kEepromSyncPulseWord);
  // The pulse length register is read-only for both sides; only the EEPROM load sets it.
  dc.load_pulse_length(pulse);
  pdi_operational = sii.config_area_valid();
  update_dl_status();
}

// ---- Esc ------------------------------------------------------------------------------------

Esc::Esc(const EscConfig& config, const Clock& clock)
    : impl_(std::make_unique<Impl>(config, clock)) {
  impl_->power_on_reset();
}

Esc::~Esc() = default;

bool Esc::process_frame(std::span<std::uint8_t> pdu, const FrameTiming& timing) {
  return impl_->process_frame(pdu, timing);
}

bool Esc::process_checked_frame(std::span<std::uint8_t> pdu, std::size_t datagrams, const FrameTiming& timing) {
  return impl_->execute_frame(pdu, datagrams, timing);
}

void Esc::count_rx_error(int port, bool forwarded) {
  if (port < 0 || port > 3) return;
  impl_->count_rx_error(port, forwarded);
}

void Esc::set_faults(const EscFaults& faults) {
  Impl& d = *impl_;
  const bool expire_now = faults.pd_watchdog_expired && !d.faults.pd_watchdog_expired;
  d.faults = faults;
  d.sii.set_no_acknowledge(faults.sii_error);
  d.dc.set_pulses_suppressed(faults.sync_lost);
  if (expire_now) {
    d.pd_watchdog.stop();
    d.pd_watchdog_expired();
  }
}

const EscFaults& Esc::faults() const { return impl_->faults; }

std::optional<std::uint16_t> Esc::pdi_eeprom_word(std::size_t word_address) const {
  if (!impl_->sii.acknowledges()) return std::nullopt;
  return impl_->sii.word(word_address);
}

void Esc::set_links(const PortLinks& links) { impl_->links_changed(links); }

bool Esc::port_forwards(int port) const {
  if (port < 0 || port > 3) return false;
  return impl_->port_implemented(port) && impl_->links.port[port] && !impl_->loop_closed(port);
}

void Esc::frame_returned(int port, Nanos now) { impl_->dc.frame_returned(port, now); }

void Esc::pdi_read(std::uint16_t address, std::span<std::uint8_t> out) {
  Impl& d = *impl_;
  d.access_now = d.clock.now();
  d.read_range(Side::Pdi, address, out);
  d.pdi_watchdog.trigger(d.access_now);
  if (d.pdi_watchdog.running() && !d.pdi_watchdog_ok) {
    d.pdi_watchdog_ok = true;
    d.update_dl_status();
  }
}

void Esc::pdi_write(std::uint16_t address, std::span<const std::uint8_t> in) {
  Impl& d = *impl_;
  d.access_now = d.clock.now();
  d.write_range(Side::Pdi, address, in);
  d.pdi_watchdog.trigger(d.access_now);
  if (d.pdi_watchdog.running() && !d.pdi_watchdog_ok) {
    d.pdi_watchdog_ok = true;
    d.update_dl_status();
  }
}

std::uint32_t Esc::pdi_irq() const {
  return impl_->al_event_request() & impl_->get32(reg::kAlEventMask);
}

void Esc::tick(Nanos now) {
  Impl& d = *impl_;
  d.access_now = now;
  d.sii.tick(now);
  d.apply_eeprom_reload();
  const SyncEvents sync = d.dc.tick(now);
  // The ET1100 maps SYNC0/1 into the AL event register only if 0x0151 asks for it; our PDI has
  // no SYNC pins, so the SYNC signals always reach the firmware through the AL event register.
  if (sync.sync0) d.set_al_event(reg::al_event::kSync0, true);
  if (sync.sync1) d.set_al_event(reg::al_event::kSync1, true);
  if (d.pd_watchdog.expire_if_due(now)) d.pd_watchdog_expired();
  if (d.pdi_watchdog.expire_if_due(now)) d.pdi_watchdog_expired();
}

Nanos Esc::next_deadline() const {
  const Impl& d = *impl_;
  return std::min({d.dc.next_deadline(), d.sii.next_deadline(), d.pd_watchdog.deadline(),
                   d.pdi_watchdog.deadline()});
}

void Esc::reset() { impl_->power_on_reset(); }

void Esc::set_dc_model(double drift_ppm, Nanos start_offset) {
  impl_->dc.set_drift_ppm(drift_ppm);
  impl_->dc.set_start_offset(start_offset);
}

std::uint8_t Esc::peek(std::uint16_t address) const { return impl_->mem[address]; }

}  // namespace vdrive::esc
