#pragma once
// Private state of one Esc and the internal operations the .cpp files share:
//   address_space.cpp     memory path: region split, register permissions, SM redirection
//   register_effects.cpp  side effects of register reads/writes, events, watchdog registers
//   data_link.cpp         ports, loop control, DL status
//   datagram_engine.cpp   frame/datagram execution and working counters
//   esc.cpp               public API glue, reset, EEPROM reload, time
// Everything is allocated at construction; nothing on the frame path allocates or locks.
#include <array>
#include <cstdint>
#include <span>

#include "common/clock.hpp"
#include "esc_model/access_side.hpp"
#include "esc_model/dc_unit.hpp"
#include "esc_model/esc.hpp"
#include "esc_model/esc_config.hpp"
#include "esc_model/fmmu.hpp"
#include "esc_model/sii_eeprom.hpp"
#include "esc_model/sync_manager.hpp"
#include "esc_model/watchdog.hpp"
#include "ethercat/datagram.hpp"
#include "ethercat/little_endian.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::esc {

// The chip's own sources name registers on nearly every line; the short name keeps them readable.
namespace reg = ecat::reg;
// The frame and datagram layout the engine walks (ethercat/datagram.hpp).
using ecat::Command;
using ecat::DatagramView;
using ecat::dlpdu_datagrams;
using ecat::EthercatHeader;
using ecat::kDatagramHeaderSize;
using ecat::kEthercatHeaderSize;
using ecat::kFrameTypeDlpdu;
using ecat::kMaxDatagramLength;
using ecat::kWkcSize;
using ecat::parse_ethercat_header;
using ecat::validate_dlpdu;

struct Esc::Impl final : PhysicalPort {
  Impl(const EscConfig& config, const Clock& clock);

  // ---- identity / resources
  EscConfig identity;          // sii_image emptied: the EEPROM owns the image
  const Clock& clock;
  std::uint32_t ram_end = 0;   // first address past process RAM
  int fmmu_count = 0;
  int sm_count = 0;

  // ---- memory: one array for the whole 64 KiB address space, plus write permissions
  static constexpr std::uint8_t kEcatWritable = 1u << 0;
  static constexpr std::uint8_t kPdiWritable = 1u << 1;
  std::array<std::uint8_t, 0x10000> mem{};
  std::array<std::uint8_t, reg::kRegisterEnd> permissions{};

  SiiEeprom sii;
  DcUnit dc;
  std::array<SyncManager, reg::kMaxSyncManagers> sms{};
  std::array<Fmmu, reg::kMaxFmmus> fmmus{};
  Watchdog pd_watchdog;
  Watchdog pdi_watchdog;

  // ---- data link
  PortLinks links;
  std::array<bool, 4> auto_closed{};  // port closed by "auto close" until DL control rewritten
  bool pdi_operational = false;
  bool pdi_watchdog_ok = false;

  // ---- injected faults (esc_faults.hpp); kept across power_on_reset
  EscFaults faults;

  // ---- frame context
  Nanos access_now = 0;                 // time of the current access (frame or PDI)
  const FrameTiming* timing = nullptr;  // set while a frame is processed
  std::uint8_t reset_progress = 0;      // ESC reset sequence 'R','E','S' at 0x0040
  bool reset_pending = false;
  std::array<std::uint8_t, kMaxDatagramLength + 1> scratch_in{};
  std::array<std::uint8_t, kMaxDatagramLength + 1> scratch_out{};

  // ---- lifecycle (esc.cpp)
  void power_on_reset();
  void load_register_defaults();
  void apply_eeprom_reload();
  void build_permissions();

  // ---- memory path (address_space.cpp). Return true if any byte was accepted.
  bool read_range(Side side, std::uint16_t address, std::span<std::uint8_t> out);
  bool write_range(Side side, std::uint16_t address, std::span<const std::uint8_t> in);
  bool read_byte(std::uint16_t address, std::uint8_t& out) override;    // ECAT, for FMMUs
  bool write_byte(std::uint16_t address, std::uint8_t value, std::uint8_t mask) override;
  // Runs wholly in process RAM go through one access (each SyncManager takes its bytes as one run);
  // anything touching registers keeps the byte-by-byte path.
  bool read_bytes(std::uint16_t address, std::span<std::uint8_t> out) override;
  bool write_bytes(std::uint16_t address, std::span<const std::uint8_t> in) override;
  std::uint32_t region_end(std::uint16_t address) const;
  bool read_region(Side side, std::uint16_t address, std::span<std::uint8_t> out);
  bool write_region(Side side, std::uint16_t address, std::span<const std::uint8_t> in,
                    std::uint8_t mask);
  void write_register_byte(Side side, std::uint16_t address, std::uint8_t value,
                           std::uint8_t mask);
  int sm_covering(std::uint16_t address) const;
  bool in_sm_window(std::uint16_t a, std::uint32_t end) const;
  std::uint32_t run_end(std::uint16_t a, int n, std::uint32_t limit) const;
  std::span<std::uint8_t> ram() { return std::span<std::uint8_t>(mem).first(ram_end); }

  // ---- register side effects and events (register_effects.cpp)
  void after_register_read(Side side, std::uint32_t lo, std::uint32_t hi);
  void after_register_write(Side side, std::uint32_t lo, std::uint32_t hi);
  void after_dc_read(std::uint32_t lo, std::uint32_t hi);
  void sm_reconfigure(int n);
  void sm_refresh(int n);
  void refresh_sms(std::uint32_t touched);  // sm_refresh for each bit set
  void configure_watchdogs();
  void trigger_pd_watchdog();
  void pd_watchdog_expired();
  void pdi_watchdog_expired();
  void count_rx_error(int port = 0, bool forwarded = false);
  void set_al_event(std::uint32_t bits, bool on);
  void set_ecat_event(std::uint16_t bits, bool on);
  std::uint32_t al_event_request() const { return get32(reg::kAlEventRequest); }
  std::uint16_t ecat_event_request() const { return get16(reg::kEcatEventRequest); }

  // ---- data link (data_link.cpp; these three inline: the segment asks them for every frame)
  bool port_implemented(int port) const { return ((identity.port_descriptor >> (2 * port)) & 0x03) != 0; }
  bool loop_closed(int port) const {
    if (!port_implemented(port)) return true;
    const auto setting = static_cast<reg::dl_control::Loop>(
        (get32(reg::kDlControl) >> (reg::dl_control::kLoopShift + 2 * port)) & 0x03);
    const bool link = links.port[port];
    switch (setting) {
      case reg::dl_control::Loop::Open: return false;
      case reg::dl_control::Loop::Closed: return true;
      case reg::dl_control::Loop::AutoClose: return !link || auto_closed[port];
      case reg::dl_control::Loop::Auto: break;
    }
    return !link;
  }
  bool port0_closed_by_master() const {
    return static_cast<reg::dl_control::Loop>((get32(reg::kDlControl) >> reg::dl_control::kLoopShift) & 0x03) ==
           reg::dl_control::Loop::Closed;
  }
  void update_dl_status();
  void dl_control_written();
  void links_changed(const PortLinks& now);

  // ---- datagrams (datagram_engine.cpp)
  bool process_frame(std::span<std::uint8_t> pdu, const FrameTiming& frame_timing);
  // The datagrams of a checked DLPDU frame (`count` of them).
  bool execute_frame(std::span<std::uint8_t> pdu, std::size_t count, const FrameTiming& frame_timing);
  void execute(DatagramView dg);
  bool addressed_configured(std::uint16_t adp) const;
  std::uint16_t physical_read(std::uint16_t ado, std::span<std::uint8_t> data, bool or_data);
  std::uint16_t physical_write(std::uint16_t ado, std::span<const std::uint8_t> data);
  std::uint16_t physical_read_write(std::uint16_t ado, std::span<std::uint8_t> data,
                                    bool or_data);
  std::uint16_t logical(std::uint32_t address, std::span<std::uint8_t> data, bool do_read,
                        bool do_write);

  // ---- little-endian register helpers on mem (no side effects); 32-bit accesses wrap at 64 KiB
  // like the address space
  std::uint16_t get16(std::uint16_t a) const { return ecat::get_le16(mem, a); }
  std::uint32_t get32(std::uint16_t a) const {
    return static_cast<std::uint32_t>(get16(a)) |
           (static_cast<std::uint32_t>(get16(static_cast<std::uint16_t>(a + 2))) << 16);
  }
  void put16(std::uint16_t a, std::uint16_t v) { ecat::put_le16(mem, a, v); }
  void put32(std::uint16_t a, std::uint32_t v) {
    put16(a, static_cast<std::uint16_t>(v));
    put16(static_cast<std::uint16_t>(a + 2), static_cast<std::uint16_t>(v >> 16));
  }
};

// [lo, hi) overlaps [reg, reg + len)
inline bool touches(std::uint32_t lo, std::uint32_t hi, std::uint32_t reg, std::uint32_t len) {
  return lo < reg + len && reg < hi;
}

}  // namespace vdrive::esc
