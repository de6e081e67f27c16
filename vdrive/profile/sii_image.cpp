#include "vdrive/profile/sii_image.hpp"

#include <algorithm>
#include <string>

#include "esc_model/sii_eeprom.hpp"
#include "ethercat/sii.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

using ecat::sii::Category;
namespace fmmu_usage = ecat::sii::fmmu_usage;

// Little-endian byte appender.
class Bytes {
public:
  void u8(std::uint8_t v) { b_.push_back(v); }
  void u16(std::uint16_t v) {
    u8(static_cast<std::uint8_t>(v));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  void u32(std::uint32_t v) {
    u16(static_cast<std::uint16_t>(v));
    u16(static_cast<std::uint16_t>(v >> 16));
  }
  void pad_to_word(std::uint8_t fill) {
    if (b_.size() % 2) u8(fill);
  }
  std::vector<std::uint8_t>& data() { return b_; }

private:
  std::vector<std::uint8_t> b_;
};

// The Strings category: index 0 means "no string"; equal texts share one index.
class StringTable {
public:
  std::uint8_t index_of(const std::string& s) {
    if (s.empty()) return 0;
    const auto it = std::find(strings_.begin(), strings_.end(), s);
    if (it != strings_.end()) return static_cast<std::uint8_t>(it - strings_.begin() + 1);
    if (strings_.size() == 255) throw ProfileError("SII: more than 255 distinct strings");
    if (s.size() > 255) throw ProfileError("SII: string longer than 255 bytes: " + s.substr(0, 32) + "...");
    strings_.push_back(s);
    return static_cast<std::uint8_t>(strings_.size());
  }
  void write(Bytes& out) const {
    out.u8(static_cast<std::uint8_t>(strings_.size()));
    for (const auto& s : strings_) {
      out.u8(static_cast<std::uint8_t>(s.size()));
      for (char c : s) out.u8(static_cast<std::uint8_t>(c));
    }
  }

private:
  std::vector<std::string> strings_;
};

void category(Bytes& image, Category type, Bytes body, std::uint8_t pad) {
  body.pad_to_word(pad);
  image.u16(static_cast<std::uint16_t>(type));
  image.u16(static_cast<std::uint16_t>(body.data().size() / 2));
  image.data().insert(image.data().end(), body.data().begin(), body.data().end());
}

// Register 0x0007 has 2 bits per port (11 = MII, 10 = EBUS); the General category a nibble per port
// (1 = MII, 3 = EBUS, 0 = not used).
std::uint16_t physical_ports(std::uint8_t port_descriptor) {
  std::uint16_t ports = 0;
  for (int p = 0; p < 4; ++p) {
    const unsigned kind = (port_descriptor >> (2 * p)) & 0x3;
    const unsigned nibble = kind == 0x3 ? 1 : kind == 0x2 ? 3 : 0;
    ports = static_cast<std::uint16_t>(ports | (nibble << (4 * p)));
  }
  return ports;
}

Bytes general(const ProductProfile& p, StringTable& strings) {
  Bytes g;
  const std::uint8_t group = strings.index_of(p.identity.group);
  g.u8(group);                                         // 0x00 group
  g.u8(0);                                             // 0x01 image (none)
  g.u8(strings.index_of(p.identity.order_code));       // 0x02 order code
  g.u8(strings.index_of(p.identity.device_name));      // 0x03 device name
  g.u8(0);                                             // 0x04 reserved
  g.u8(p.coe_details);                                 // 0x05
  g.u8(p.foe_details);                                 // 0x06
  g.u8(0);                                             // 0x07 EoE details
  g.u8(0);                                             // 0x08 SoE channels
  g.u8(0);                                             // 0x09 DS402 channels (reserved)
  g.u8(0);                                             // 0x0A SysmanClass (reserved)
  g.u8(p.explicit_device_id ? ecat::sii::kGeneralFlagIdentAlStatus : 0); // 0x0B flags
  g.u16(0);                                            // 0x0C current on E-Bus: RJ45 device
  g.u16(physical_ports(p.esc.port_descriptor));        // 0x0E physical ports
  g.u16(0);                                            // 0x10 physical memory address (IdentPhyM unused)
  for (int i = 0x12; i < 0x20; ++i) g.u8(0);           // 0x12..0x1F reserved
  return g;
}

Bytes fmmus(const ProductProfile& p) {
  Bytes f;
  if (!p.fmmu_usage.empty()) {
    for (const std::uint8_t usage : p.fmmu_usage) f.u8(usage);
    return f;
  }
  constexpr std::uint8_t order[] = {fmmu_usage::kOutputs, fmmu_usage::kInputs, fmmu_usage::kMailboxState};
  for (std::uint8_t i = 0; i < p.esc.fmmu_count; ++i) f.u8(i < 3 ? order[i] : fmmu_usage::kUnused);
  return f;  // padded with 0xFF ("not used") by category()
}

Bytes sync_managers(const ProductProfile& p) {
  Bytes s;
  for (const auto& sm : p.sync_managers) {
    s.u16(sm.start);
    s.u16(sm.length);
    s.u8(sm.control);
    s.u8(0);                                   // status, written by the ESC
    s.u8(sm.enable ? 0x01 : 0x00);             // enable byte
    s.u8(static_cast<std::uint8_t>(sm.kind));  // 1 mbx out, 2 mbx in, 3 outputs, 4 inputs
  }
  return s;
}

Bytes pdo(const PdoSpec& pdo, StringTable& strings) {
  Bytes b;
  b.u16(pdo.index);
  b.u8(static_cast<std::uint8_t>(pdo.entries.size()));
  b.u8(pdo.sync_manager);
  b.u8(0);  // DC synchronisation
  b.u8(strings.index_of(pdo.name));
  std::uint16_t flags = pdo.sync_manager != 0xFF ? ecat::sii::kPdoFlagDefault : 0;
  if (pdo.fixed) flags |= ecat::sii::kPdoFlagFixedContent;
  b.u16(flags);
  for (const auto& e : pdo.entries) {
    b.u16(e.index);
    b.u8(e.subindex);
    b.u8(strings.index_of(e.name));
    b.u8(e.data_type);
    b.u8(e.bit_length);
    b.u16(0);  // flags
  }
  return b;
}

}  // namespace

std::vector<std::uint8_t> build_sii_image(const ProductProfile& p) {
  Bytes image;
  // Words 0x00-0x07: ESC configuration area, loaded into the ESC at power-on.
  image.u16(p.esc.pdi_control);
  image.u16(p.esc.pdi_config);
  image.u16(p.esc.sync_pulse_length);
  image.u16(p.esc.extended_pdi_config);
  image.u16(p.esc.station_alias);
  image.u32(0);  // words 5-6 reserved
  image.u8(esc::sii_config_crc(std::span(image.data()).first(14)));
  image.u8(0);
  // Words 0x08-0x0F: identity.
  image.u32(p.identity.vendor_id);
  image.u32(p.identity.product_code);
  image.u32(p.identity.revision);
  image.u32(p.identity.serial);
  // Words 0x10-0x13: execution delay, port 0/1 delays, reserved.
  image.u32(0);
  image.u32(0);
  // Words 0x14-0x17: bootstrap mailbox (0 when the product has no Boot state).
  const Mailbox& mb = p.mailbox;
  const bool boot = p.has_bootstrap && mb.boot_rx_offset;
  image.u16(boot ? *mb.boot_rx_offset : 0);
  image.u16(boot ? *mb.boot_rx_size : 0);
  image.u16(boot ? *mb.boot_tx_offset : 0);
  image.u16(boot ? *mb.boot_tx_size : 0);
  // Words 0x18-0x1C: standard mailbox and protocols.
  image.u16(mb.rx_offset);
  image.u16(mb.rx_size);
  image.u16(mb.tx_offset);
  image.u16(mb.tx_size);
  image.u16(mb.protocols);
  // Words 0x1D-0x3D reserved; 0x3E size as (kbit - 1); 0x3F version 1.
  image.data().resize(ecat::sii::kWordEepromSize * 2, 0);
  image.u16(static_cast<std::uint16_t>(p.esc.eeprom_bytes * 8 / 1024 - 1));
  image.u16(1);

  // Categories from word 0x40. Strings come first but are only complete once every other
  // category has taken its indexes, so the others are built before it is written.
  StringTable strings;
  strings.index_of(p.identity.device_name);  // string 1: the device name (1008h)
  strings.index_of(p.identity.vendor_name);
  Bytes gen = general(p, strings);
  // One TxPDO and one RxPDO category, each listing its PDOs one after the other (ETG.2010; SOEM
  // and IgH read every PDO of the first category of each kind).
  Bytes tx, rx;
  for (const auto& t : p.tx_pdos) {
    Bytes b = pdo(t, strings);
    tx.data().insert(tx.data().end(), b.data().begin(), b.data().end());
  }
  for (const auto& r : p.rx_pdos) {
    Bytes b = pdo(r, strings);
    rx.data().insert(rx.data().end(), b.data().begin(), b.data().end());
  }
  Bytes str;
  strings.write(str);
  category(image, Category::Strings, std::move(str), 0x00);
  category(image, Category::General, std::move(gen), 0x00);
  category(image, Category::Fmmu, fmmus(p), 0xFF);
  category(image, Category::SyncManager, sync_managers(p), 0x00);
  if (!p.tx_pdos.empty()) category(image, Category::TxPdo, std::move(tx), 0x00);
  if (!p.rx_pdos.empty()) category(image, Category::RxPdo, std::move(rx), 0x00);
  image.u16(static_cast<std::uint16_t>(Category::End));

  auto& bytes = image.data();
  if (bytes.size() > p.esc.eeprom_bytes)
    throw ProfileError(p.id + ": SII image needs " + std::to_string(bytes.size()) + " bytes, EEPROM has " +
                       std::to_string(p.esc.eeprom_bytes));
  bytes.resize(p.esc.eeprom_bytes, 0xFF);  // an erased EEPROM reads 0xFF
  return std::move(bytes);
}

esc::EscConfig make_esc_config(const ProductProfile& p) {
  esc::EscConfig c;
  c.type = p.esc.type;
  c.revision = p.esc.revision;
  c.build = p.esc.build;
  c.fmmu_count = p.esc.fmmu_count;
  c.sm_count = p.esc.sm_count;
  c.ram_kib = p.esc.ram_kib;
  c.port_descriptor = p.esc.port_descriptor;
  c.features = p.esc.features;
  c.sii_image = build_sii_image(p);
  return c;
}

}  // namespace vdrive::profile
