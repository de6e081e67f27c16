#pragma once
// Typed PDI access for the firmware: little-endian register reads/writes over esc::Esc's
// pdi_read/pdi_write (addresses from ethercat/registers.hpp). Everything goes through
// the PDI so PDI side effects happen exactly as on silicon (reading AL Control clears its event,
// reading an SM activation register clears the "SM changed" event).
// No allocation, no locks: safe on the frame path.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "esc_model/esc.hpp"
#include "ethercat/little_endian.hpp"
#include "ethercat/registers.hpp"

namespace vdrive::firmware {

// Register addresses and bits: the EtherCAT register map (ethercat/registers.hpp).
namespace reg = ecat::reg;
namespace al_event = ecat::reg::al_event;

// One SyncManager's channel registers as the PDI reads them (0x0800 + 8n .. +7).
struct SmChannel {
  std::uint16_t start = 0;    // +0 physical start address
  std::uint16_t length = 0;   // +2
  std::uint8_t control = 0;   // +4 (bits 1:0 mode, 3:2 direction, 5 PDI IRQ, 6 watchdog)
  std::uint8_t status = 0;    // +5
  std::uint8_t activate = 0;  // +6 (bit0 enable); reading it clears the "SM changed" event
  std::uint8_t pdi_control = 0;  // +7

  bool enabled() const { return (activate & reg::sm::kEnable) != 0; }
};

inline constexpr int kMaxSyncManagers = reg::kMaxSyncManagers;

// Address of SyncManager n's channel register at `offset` (reg::sm::k*), 0x0800 + 8n + offset.
inline std::uint16_t sm_register(int n, std::uint16_t offset = 0) {
  return static_cast<std::uint16_t>(reg::kSm0 + reg::kSmStride * n + offset);
}

class Pdi {
public:
  explicit Pdi(esc::Esc& esc) : esc_(esc) {}

  std::uint8_t read_u8(std::uint16_t address) {
    std::array<std::uint8_t, 1> b{};
    esc_.pdi_read(address, b);
    return b[0];
  }
  std::uint16_t read_u16(std::uint16_t address) {
    std::array<std::uint8_t, 2> b{};
    esc_.pdi_read(address, b);
    return ecat::get_le16(b.data());
  }
  std::uint32_t read_u32(std::uint16_t address) {
    std::array<std::uint8_t, 4> b{};
    esc_.pdi_read(address, b);
    return ecat::get_le32(b.data());
  }
  void write_u8(std::uint16_t address, std::uint8_t value) {
    const std::array<std::uint8_t, 1> b{value};
    esc_.pdi_write(address, b);
  }
  // Burst access (mailbox buffers): one PDI access, so SyncManager side effects happen once.
  void read(std::uint16_t address, std::span<std::uint8_t> out) { esc_.pdi_read(address, out); }
  void write(std::uint16_t address, std::span<const std::uint8_t> in) { esc_.pdi_write(address, in); }
  void write_u16(std::uint16_t address, std::uint16_t value) {
    std::array<std::uint8_t, 2> b{};
    ecat::put_le16(b.data(), value);
    esc_.pdi_write(address, b);
  }
  void write_u32(std::uint16_t address, std::uint32_t value) {
    std::array<std::uint8_t, 4> b{};
    ecat::put_le32(b.data(), value);
    esc_.pdi_write(address, b);
  }

  // Reads SyncManager n's eight channel bytes in one access (as a µC would, one burst).
  SmChannel read_sm(int n) { return read_sm_bytes(n, 8); }
  // Reads SyncManager n's start, length, control and status (bytes 0-5) in one access; unlike
  // read_sm it does not touch the activate register, so the "SM changed" event is left alone
  // (activate and PDI control read as 0).
  SmChannel read_sm_window(int n) { return read_sm_bytes(n, 6); }

  std::uint32_t irq() const { return esc_.pdi_irq(); }
  // The SII EEPROM chip read by the microcontroller itself (esc::Esc::pdi_eeprom_word).
  std::optional<std::uint16_t> eeprom_word(std::size_t word_address) const { return esc_.pdi_eeprom_word(word_address); }

private:
  SmChannel read_sm_bytes(int n, std::size_t count) {
    std::array<std::uint8_t, 8> b{};
    esc_.pdi_read(sm_register(n), std::span(b).first(count));
    SmChannel sm;
    sm.start = static_cast<std::uint16_t>(b[0] | (b[1] << 8));
    sm.length = static_cast<std::uint16_t>(b[2] | (b[3] << 8));
    sm.control = b[4];
    sm.status = b[5];
    sm.activate = b[6];
    sm.pdi_control = b[7];
    return sm;
  }

  esc::Esc& esc_;
};

}  // namespace vdrive::firmware
