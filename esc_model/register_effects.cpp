// What the silicon does when certain registers are read or written, and the event registers
// (ECAT event request 0x0210, AL event request 0x0220) those actions drive.
#include <algorithm>

#include "esc_model/esc_impl.hpp"

namespace vdrive::esc {

void Esc::Impl::set_al_event(std::uint32_t bits, bool on) {
  const std::uint32_t v = al_event_request();
  put32(reg::kAlEventRequest, on ? (v | bits) : (v & ~bits));
}

void Esc::Impl::set_ecat_event(std::uint16_t bits, bool on) {
  const std::uint16_t v = ecat_event_request();
  put16(reg::kEcatEventRequest,
        on ? static_cast<std::uint16_t>(v | bits) : static_cast<std::uint16_t>(v & ~bits));
}

void Esc::Impl::after_register_read(Side side, std::uint32_t lo, std::uint32_t hi) {
  if (side == Side::Pdi) {
    if (touches(lo, hi, reg::kAlControl, 2)) set_al_event(reg::al_event::kAlControl, false);
    if (touches(lo, hi, reg::kWatchdogStatusProcessData, 2)) {
      set_al_event(reg::al_event::kPdWatchdog, false);
    }
    if (touches(lo, hi, reg::kSm0, reg::kSmStride * sm_count)) {
      for (int n = 0; n < sm_count; ++n) {
        if (touches(lo, hi, reg::kSm0 + reg::kSmStride * n + reg::sm::kActivate, 1)) {
          set_al_event(reg::al_event::kSmActivation, false);
        }
      }
    }
  } else {
    if (touches(lo, hi, reg::kDlStatus, 2)) set_ecat_event(reg::ecat_event::kDlStatus, false);
    if (touches(lo, hi, reg::kAlStatus, 2)) set_ecat_event(reg::ecat_event::kAlStatus, false);
  }
}

void Esc::Impl::after_dc_read(std::uint32_t lo, std::uint32_t hi) {
  if (touches(lo, hi, reg::kDcSync0Status, 1)) set_al_event(reg::al_event::kSync0, false);
  if (touches(lo, hi, reg::kDcSync1Status, 1)) set_al_event(reg::al_event::kSync1, false);
}

void Esc::Impl::after_register_write(Side side, std::uint32_t lo, std::uint32_t hi) {
  if (side == Side::Ecat) {
    if (touches(lo, hi, reg::kAlControl, 2)) {
      set_al_event(reg::al_event::kAlControl, true);
      if (mem[reg::kEscConfiguration] & reg::kEscConfigDeviceEmulation) {
        // Device emulation: no firmware, the ESC answers the requested state itself.
        put16(reg::kAlStatus, get16(reg::kAlControl) & reg::kAlStateBits);
        set_ecat_event(reg::ecat_event::kAlStatus, true);
      }
    }
    if (touches(lo, hi, reg::kDlControl, 4)) dl_control_written();
    if (touches(lo, hi, reg::kRxErrorCounter, reg::kPdiErrors + 1 - reg::kRxErrorCounter)) {
      std::fill(mem.begin() + reg::kRxErrorCounter, mem.begin() + reg::kPdiErrors + 1,
                std::uint8_t{0});
    }
    if (touches(lo, hi, reg::kLostLinkCounter, reg::kLostLinkCounterEnd - reg::kLostLinkCounter)) {
      std::fill(mem.begin() + reg::kLostLinkCounter, mem.begin() + reg::kLostLinkCounterEnd,
                std::uint8_t{0});
    }
    if (touches(lo, hi, reg::kWatchdogCounterProcessData, 2)) {
      mem[reg::kWatchdogCounterProcessData] = 0;
      mem[reg::kWatchdogCounterPdi] = 0;
    }
    if (touches(lo, hi, reg::kWatchdogDivider, 2) ||
        touches(lo, hi, reg::kWatchdogTimePdi, 2) ||
        touches(lo, hi, reg::kWatchdogTimeProcessData, 2)) {
      configure_watchdogs();
    }
    for (int n = 0; n < fmmu_count; ++n) {
      const auto base = static_cast<std::uint16_t>(reg::kFmmu0 + reg::kFmmuStride * n);
      if (touches(lo, hi, base, reg::kFmmuStride)) {
        fmmus[static_cast<std::size_t>(n)] =
            Fmmu::decode(std::span<const std::uint8_t, 16>(mem.data() + base, 16));
      }
    }
  } else {
    if (touches(lo, hi, reg::kAlStatus, 2)) set_ecat_event(reg::ecat_event::kAlStatus, true);
  }
  for (int n = 0; n < sm_count; ++n) {
    if (touches(lo, hi, reg::kSm0 + reg::kSmStride * n, reg::kSmStride)) sm_reconfigure(n);
  }
}

void Esc::Impl::sm_reconfigure(int n) {
  const auto base = static_cast<std::uint16_t>(reg::kSm0 + reg::kSmStride * n);
  sms[static_cast<std::size_t>(n)].configure(
      SyncManager::Registers(mem.data() + base, reg::kSmStride));
  sm_refresh(n);
}

void Esc::Impl::sm_refresh(int n) {
  const SyncManager& sm = sms[static_cast<std::size_t>(n)];
  mem[reg::kSm0 + reg::kSmStride * n + reg::sm::kStatus] = sm.status();
  set_al_event(1u << (reg::al_event::kSmShift + n), sm.pdi_event());
  if (n < 8) {
    set_ecat_event(static_cast<std::uint16_t>(1u << (reg::ecat_event::kSmShift + n)),
                   sm.ecat_event());
  }
}

void Esc::Impl::configure_watchdogs() {
  const std::uint16_t divider = get16(reg::kWatchdogDivider);
  pd_watchdog.configure(divider, get16(reg::kWatchdogTimeProcessData));
  pdi_watchdog.configure(divider, get16(reg::kWatchdogTimePdi));
}

void Esc::Impl::trigger_pd_watchdog() {
  if (faults.pd_watchdog_expired) return;  // injected: stays expired whatever the master writes
  pd_watchdog.trigger(access_now);
  if (pd_watchdog.running()) mem[reg::kWatchdogStatusProcessData] |= 0x01;
}

void Esc::Impl::pd_watchdog_expired() {
  mem[reg::kWatchdogStatusProcessData] &= static_cast<std::uint8_t>(~0x01);
  std::uint8_t& count = mem[reg::kWatchdogCounterProcessData];
  if (count < reg::kCounterMax) ++count;
  set_al_event(reg::al_event::kPdWatchdog, true);
}

void Esc::Impl::pdi_watchdog_expired() {
  pdi_watchdog_ok = false;
  std::uint8_t& count = mem[reg::kWatchdogCounterPdi];
  if (count < reg::kCounterMax) ++count;
  update_dl_status();
}

void Esc::Impl::count_rx_error(int port, bool forwarded) {
  // A malformed frame counts as an invalid frame at port 0, where processing happens; a frame
  // already marked bad by an ESC before this one counts as a forwarded error at its port.
  std::uint8_t& count = forwarded ? mem[reg::kForwardedRxErrorCounter + port]
                                  : mem[reg::kRxErrorCounter + 2 * port];
  if (count < reg::kCounterMax) ++count;
}

}  // namespace vdrive::esc
