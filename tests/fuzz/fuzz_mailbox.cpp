// libFuzzer target: the mailbox/CoE path of a Pre-Op slave. Arbitrary bytes become mailbox writes
// into SM0 (over the wire, APWR), SM1 reads, repeat requests and AL state requests, on one of the
// three products with its firmware (SlaveFirmware, all modules installed).
//
// Input: byte 0 picks the product; then records [op(1) length(1) bytes(length)]:
//   op & 3 == 0: the bytes are written into SM0 (zero-padded to its length); op bit2 patches the
//               header length to the bytes after it and op bit3 the type to CoE, so most inputs
//               reach the SDO server and SDO information;
//   op & 3 == 1: SM1 is read (as a master polls it);
//   op & 3 == 2: the SM1 repeat request bit is toggled;
//   op & 3 == 3: AL control = bytes[0] (any value, incl. undefined states); first, op bit2 moves
//               SM0/SM1 to the product's bootstrap mailbox (as a master does before Init->Boot,
//               so FoE in Boot is reached) and op bit3 back to the standard mailbox.
// SM0 writes and SM1 reads go to the mailbox in effect. Parameter files go to a temporary
// directory (1010h "save" may be reached).
#include <stdlib.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace {

struct Slave {
  explicit Slave(const std::string& id)
      : product(vdrive::profile::load_profile(id)),
        esc(vdrive::profile::make_esc_config(product), clock),
        firmware(product, esc) {}

  void datagram(std::uint8_t cmd, std::uint16_t ado, const std::uint8_t* data, std::size_t n) {
    const std::size_t dg_len = 10 + n + 2;
    pdu.assign({static_cast<std::uint8_t>(dg_len & 0xFF),
                static_cast<std::uint8_t>(0x10 | ((dg_len >> 8) & 0x07)), cmd, 0x00, 0x00, 0x00,
                static_cast<std::uint8_t>(ado & 0xFF), static_cast<std::uint8_t>(ado >> 8),
                static_cast<std::uint8_t>(n & 0xFF), static_cast<std::uint8_t>((n >> 8) & 0x07),
                0x00, 0x00});
    if (data != nullptr) {
      pdu.insert(pdu.end(), data, data + n);
    } else {
      pdu.resize(pdu.size() + n, 0);
    }
    pdu.push_back(0);
    pdu.push_back(0);
    esc.process_frame(pdu, vdrive::esc::FrameTiming{clock.now()});
    if (esc.pdi_irq() != 0) firmware.on_irq(clock.now());
    clock.advance(50'000);
    if (firmware.next_deadline() <= clock.now()) firmware.tick(clock.now());
  }
  void write(std::uint16_t ado, std::vector<std::uint8_t> bytes) {
    datagram(0x02, ado, bytes.data(), bytes.size());
  }

  // Power cycle, mailbox SMs as the SII says, PreOp.
  void reset() {
    clock.set(0);
    esc.reset();
    firmware.power_on(0);
    mailbox_layout(false);
    write(0x0120, {0x02, 0x00});
    repeat = 0;
  }

  // SM0/SM1 as the standard or (if the product has one) the bootstrap mailbox.
  void mailbox_layout(bool boot) {
    const auto& mbx = product.mailbox;
    if (boot && !(mbx.boot_rx_offset && mbx.boot_rx_size && mbx.boot_tx_offset && mbx.boot_tx_size)) return;
    for (int n = 0; n < 2; ++n) {
      const auto& sm = product.sync_managers.at(static_cast<std::size_t>(n));
      std::uint16_t start = sm.start, length = sm.length;
      if (boot) {
        start = n == 0 ? *mbx.boot_rx_offset : *mbx.boot_tx_offset;
        length = n == 0 ? *mbx.boot_rx_size : *mbx.boot_tx_size;
      }
      (n == 0 ? sm0 : sm1) = {start, length};
      const auto base = static_cast<std::uint16_t>(0x0800 + 8 * n);
      write(static_cast<std::uint16_t>(base + 6), {0x00});  // the configuration is locked while enabled
      write(base, {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
                   static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8), sm.control});
      write(static_cast<std::uint16_t>(base + 6), {0x01});
    }
  }

  struct Window {
    std::uint16_t start = 0, length = 0;
  };
  Window sm0, sm1;  // the mailbox in effect

  vdrive::VirtualClock clock;
  vdrive::profile::ProductProfile product;
  vdrive::esc::Esc esc;
  vdrive::firmware::SlaveFirmware firmware;
  std::vector<std::uint8_t> pdu;
  std::vector<std::uint8_t> window;
  std::uint8_t repeat = 0;
};

std::array<std::unique_ptr<Slave>, 3>& slaves() {
  static std::array<std::unique_ptr<Slave>, 3> s = [] {
    static std::string dir = (std::filesystem::temp_directory_path() / "vdrive-fuzz-XXXXXX").string();
    ::setenv("VDRIVE_STATE_DIR", ::mkdtemp(dir.data()), 1);
    return std::array<std::unique_ptr<Slave>, 3>{std::make_unique<Slave>("a6b"),
                                                 std::make_unique<Slave>("ds5c1"),
                                                 std::make_unique<Slave>("ds1000a")};
  }();
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  Slave& s = *slaves()[data[0] % 3];
  s.reset();
  const Slave::Window& sm0 = s.sm0;
  const Slave::Window& sm1 = s.sm1;
  std::size_t at = 1;
  while (at + 2 <= size) {
    const std::uint8_t op = data[at];
    std::size_t len = data[at + 1];
    at += 2;
    if (len > size - at) len = size - at;
    switch (op & 3) {
      case 0: {
        s.window.assign(sm0.length, 0);
        std::copy_n(data + at, std::min<std::size_t>(len, sm0.length), s.window.begin());
        if ((op & 0x04) && len >= 6) {
          const std::size_t body = std::min<std::size_t>(len, sm0.length) - 6;
          s.window[0] = static_cast<std::uint8_t>(body);
          s.window[1] = static_cast<std::uint8_t>(body >> 8);
        }
        if ((op & 0x08) && s.window.size() > 5) {
          s.window[5] = static_cast<std::uint8_t>((s.window[5] & 0xF0) | 0x03);
        }
        s.datagram(0x02, sm0.start, s.window.data(), s.window.size());
        break;
      }
      case 1: s.datagram(0x01, sm1.start, nullptr, sm1.length); break;
      case 2:
        s.repeat ^= 0x02;
        s.write(0x080E, {static_cast<std::uint8_t>(0x01 | s.repeat)});
        break;
      case 3:
        if (op & 0x0C) s.mailbox_layout((op & 0x04) != 0);
        s.write(0x0120, {len > 0 ? data[at] : std::uint8_t{0x02}, 0x00});
        break;
    }
    at += len;
  }
  return 0;
}
