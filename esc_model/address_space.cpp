// The memory path every access takes, ECAT or PDI, physical or through an FMMU:
//   0x0000-0x0FFF registers: per-byte write permission per side, then side effects
//   0x0500-0x050F SII EEPROM interface, 0x0900-0x09FF DC unit: delegated as whole spans, so
//                 multi-byte registers (e.g. 64-bit system time) are accessed atomically
//   0x0F00-0x0F03 digital output data: a register, or a SyncManager's window where one covers it
//   0x1000-ram_end process RAM, redirected through enabled SyncManagers
//   above ram_end: not backed; reads give 0, writes are dropped (the access still counts)
// Addresses wrap at 64 KiB like the ESC's 16-bit offset.
#include <algorithm>

#include "esc_model/esc_impl.hpp"

namespace vdrive::esc {

std::uint32_t Esc::Impl::region_end(std::uint16_t a) const {
  if (a < reg::kSiiFirst) return reg::kSiiFirst;
  if (a < reg::kSiiEnd) return reg::kSiiEnd;
  if (a < reg::kDcFirst) return reg::kDcFirst;
  if (a < reg::kDcEnd) return reg::kDcEnd;
  if (a < reg::kDigitalOutputData) return reg::kDigitalOutputData;
  if (a < reg::kDigitalOutputDataEnd) return reg::kDigitalOutputDataEnd;
  if (a < reg::kRegisterEnd) return reg::kRegisterEnd;
  if (a < ram_end) return ram_end;
  return 0x10000;
}

bool Esc::Impl::read_range(Side side, std::uint16_t address, std::span<std::uint8_t> out) {
  bool any = out.empty();
  std::size_t i = 0;
  while (i < out.size()) {
    const auto a = static_cast<std::uint16_t>(address + i);
    const std::size_t chunk = std::min<std::size_t>(out.size() - i, region_end(a) - a);
    any = read_region(side, a, out.subspan(i, chunk)) || any;
    i += chunk;
  }
  return any;
}

bool Esc::Impl::write_range(Side side, std::uint16_t address, std::span<const std::uint8_t> in) {
  bool any = in.empty();
  std::size_t i = 0;
  while (i < in.size()) {
    const auto a = static_cast<std::uint16_t>(address + i);
    const std::size_t chunk = std::min<std::size_t>(in.size() - i, region_end(a) - a);
    any = write_region(side, a, in.subspan(i, chunk), 0xFF) || any;
    i += chunk;
  }
  return any;
}

bool Esc::Impl::read_byte(std::uint16_t address, std::uint8_t& out) {
  return read_region(Side::Ecat, address, std::span<std::uint8_t>(&out, 1));
}

bool Esc::Impl::write_byte(std::uint16_t address, std::uint8_t value, std::uint8_t mask) {
  return write_region(Side::Ecat, address, std::span<const std::uint8_t>(&value, 1), mask);
}

bool Esc::Impl::read_bytes(std::uint16_t address, std::span<std::uint8_t> out) {
  if (address < reg::kRegisterEnd || address + out.size() > ram_end) {
    return PhysicalPort::read_bytes(address, out);
  }
  return read_region(Side::Ecat, address, out);
}

bool Esc::Impl::write_bytes(std::uint16_t address, std::span<const std::uint8_t> in) {
  if (address < reg::kRegisterEnd || address + in.size() > ram_end) {
    return PhysicalPort::write_bytes(address, in);
  }
  return write_region(Side::Ecat, address, in, 0xFF);
}

// An access to the digital output data that an enabled SyncManager covers goes through it, as
// process RAM does (region_end() keeps such an access within 0x0F00-0x0F03).
bool Esc::Impl::in_sm_window(std::uint16_t a, std::uint32_t end) const {
  if (a < reg::kDigitalOutputData || a >= reg::kDigitalOutputDataEnd) return false;
  for (std::uint32_t at = a; at < end; ++at)
    if (sm_covering(static_cast<std::uint16_t>(at)) >= 0) return true;
  return false;
}

int Esc::Impl::sm_covering(std::uint16_t address) const {
  for (int n = 0; n < sm_count; ++n) {
    if (sms[static_cast<std::size_t>(n)].covers(address)) return n;
  }
  return -1;
}

// Bytes from `a` on that go to the same place as `a`: SM n's window (n = sm_covering(a)) or plain
// RAM (n < 0), up to `limit`. A lower-numbered SM wins an overlap, as sm_covering gives per byte,
// so a run also stops where the window of any SM before n begins.
std::uint32_t Esc::Impl::run_end(std::uint16_t a, int n, std::uint32_t limit) const {
  std::uint32_t end = n < 0 ? limit : std::min(limit, sms[static_cast<std::size_t>(n)].end());
  const int before = n < 0 ? sm_count : n;
  for (int m = 0; m < before; ++m) {
    const SyncManager& sm = sms[static_cast<std::size_t>(m)];
    if (!sm.enabled() || sm.end() <= a) continue;
    if (sm.start() > a) end = std::min<std::uint32_t>(end, sm.start());
  }
  return end;
}

bool Esc::Impl::read_region(Side side, std::uint16_t a, std::span<std::uint8_t> out) {
  const std::uint32_t end = a + static_cast<std::uint32_t>(out.size());
  if (a >= reg::kSiiFirst && a < reg::kSiiEnd) {
    sii.read(static_cast<std::uint16_t>(a - reg::kSiiFirst), out, access_now, side == Side::Ecat);
    return true;
  }
  if (a >= reg::kDcFirst && a < reg::kDcEnd) {
    dc.read(static_cast<std::uint16_t>(a - reg::kDcFirst), out, access_now);
    after_dc_read(a, end);
    return true;
  }
  if (a < reg::kRegisterEnd && !in_sm_window(a, end)) {
    std::copy_n(mem.begin() + a, out.size(), out.begin());
    after_register_read(side, a, end);
    return true;
  }
  if (a >= ram_end) {
    std::fill(out.begin(), out.end(), std::uint8_t{0});
    return true;
  }
  bool any = false;
  std::uint32_t touched = 0;  // SMs whose status and events are refreshed once, after the access
  for (std::uint32_t at = a; at < end;) {
    const auto at16 = static_cast<std::uint16_t>(at);
    const int n = sm_covering(at16);
    const std::uint32_t stop = run_end(at16, n, end);
    const auto part = out.subspan(at - a, stop - at);
    if (n < 0) {
      std::copy_n(mem.begin() + at, part.size(), part.begin());
      any = true;
    } else {
      any = sms[static_cast<std::size_t>(n)].read(side, at16, part, ram()).ok || any;
      touched |= 1u << n;
    }
    at = stop;
  }
  refresh_sms(touched);
  return any;
}

bool Esc::Impl::write_region(Side side, std::uint16_t a, std::span<const std::uint8_t> in,
                             std::uint8_t mask) {
  const std::uint32_t end = a + static_cast<std::uint32_t>(in.size());
  if ((a >= reg::kSiiFirst && a < reg::kSiiEnd) || (a >= reg::kDcFirst && a < reg::kDcEnd)) {
    // Delegated windows take whole bytes; a partial (bit-mapped) write merges with the current
    // value first. Only FMMU bit mappings produce those, one byte at a time.
    std::uint8_t merged = 0;
    std::span<const std::uint8_t> data = in;
    if (mask != 0xFF) {
      std::uint8_t current = 0;
      read_region(side, a, std::span<std::uint8_t>(&current, 1));
      merged = static_cast<std::uint8_t>((current & ~mask) | (in[0] & mask));
      data = std::span<const std::uint8_t>(&merged, 1);
    }
    if (a < reg::kSiiEnd) {
      sii.write(static_cast<std::uint16_t>(a - reg::kSiiFirst), data, access_now,
                side == Side::Ecat);
      apply_eeprom_reload();
    } else {
      dc.write(static_cast<std::uint16_t>(a - reg::kDcFirst), data, access_now,
               side == Side::Ecat);
      if (side == Side::Ecat && timing != nullptr && a == reg::kDcReceiveTimePort0) {
        dc.latch_receive_times(*timing);
      }
    }
    return true;
  }
  if (a < reg::kRegisterEnd && !in_sm_window(a, end)) {
    for (std::size_t i = 0; i < in.size(); ++i) {
      write_register_byte(side, static_cast<std::uint16_t>(a + i), in[i], mask);
    }
    after_register_write(side, a, end);
    return true;
  }
  if (a >= ram_end) return true;
  bool any = false;
  std::uint32_t touched = 0;
  for (std::uint32_t at = a; at < end;) {
    const auto at16 = static_cast<std::uint16_t>(at);
    const int n = sm_covering(at16);
    const std::uint32_t stop = run_end(at16, n, end);
    const auto part = in.subspan(at - a, stop - at);
    if (n < 0) {
      for (std::size_t i = 0; i < part.size(); ++i) {
        mem[at + i] = static_cast<std::uint8_t>((mem[at + i] & ~mask) | (part[i] & mask));
      }
      any = true;
    } else {
      SyncManager& sm = sms[static_cast<std::size_t>(n)];
      const SyncManager::Result r = sm.write(side, at16, part, mask, ram());
      any = any || r.ok;
      if (r.completed && side == Side::Ecat && sm.watchdog_trigger()) trigger_pd_watchdog();
      touched |= 1u << n;
    }
    at = stop;
  }
  refresh_sms(touched);
  return any;
}

// Status and events depend only on an SM's state after the access, and nothing observes them in
// between, so one refresh per SM and access gives what a refresh per byte gave.
void Esc::Impl::refresh_sms(std::uint32_t touched) {
  for (int n = 0; touched != 0; ++n, touched >>= 1) {
    if (touched & 1u) sm_refresh(n);
  }
}

void Esc::Impl::write_register_byte(Side side, std::uint16_t a, std::uint8_t value,
                                    std::uint8_t mask) {
  const std::uint8_t allowed = side == Side::Ecat ? kEcatWritable : kPdiWritable;
  if ((permissions[a] & allowed) == 0) return;
  if (a >= reg::kSm0 && a < reg::kSm0 + reg::kSmStride * reg::kMaxSyncManagers) {
    const std::uint16_t base = a - (a - reg::kSm0) % reg::kSmStride;
    const std::uint16_t offset = a - base;
    // SM configuration can only be changed while the SM is disabled by the master.
    if (offset < reg::sm::kStatus && (mem[base + reg::sm::kActivate] & reg::sm::kEnable) != 0) {
      return;
    }
    const auto next = static_cast<std::uint8_t>((mem[a] & ~mask) | (value & mask));
    if (offset == reg::sm::kActivate && side == Side::Ecat && next != mem[a]) {
      set_al_event(reg::al_event::kSmActivation, true);
    }
    mem[a] = next;
    return;
  }
  if (a == reg::kEscResetEcat && side == Side::Ecat) {
    // Reset sequence: 'R', 'E', 'S' in consecutive writes; anything else restarts it.
    if (value == reg::kResetSequence[reset_progress]) {
      ++reset_progress;
    } else {
      reset_progress = value == reg::kResetSequence[0] ? 1 : 0;
    }
    if (reset_progress == 3) {
      reset_progress = 0;
      reset_pending = true;
    }
    mem[a] = reset_progress;
    return;
  }
  mem[a] = static_cast<std::uint8_t>((mem[a] & ~mask) | (value & mask));
}

}  // namespace vdrive::esc
