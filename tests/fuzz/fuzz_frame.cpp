// libFuzzer target: arbitrary bytes as EtherCAT frame PDUs through a line of three ESCs.
//
// Input: a sequence of records [flags(1) length(2, LE) pdu(length)]. Flag bit 0 patches the
// EtherCAT header to a type-1 frame whose length matches the record, so the fuzzer reaches the
// datagram engine instead of spending its time on the header check. Between frames the clock
// advances and each ESC's "firmware" touches the mailbox and process-data areas over the PDI,
// so SyncManager handshakes and watchdogs move too. The ESCs start configured like a slave in
// SAFE-OP (station addresses, mailbox and 3-buffer SMs, FMMUs), which a fuzzer would otherwise
// need many frames to reach.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "esc_model/sii_eeprom.hpp"
#include "tests/fuzz/fuzz_records.hpp"

namespace {

using vdrive::Nanos;
using vdrive::VirtualClock;
using vdrive::esc::Esc;
using vdrive::esc::EscConfig;
using vdrive::esc::FrameTiming;

EscConfig make_config() {
  EscConfig c;
  c.sii_image.assign(2048, 0);
  c.sii_image[0] = 0x05;
  c.sii_image[1] = 0x0C;
  c.sii_image[14] = vdrive::esc::sii_config_crc(
      std::span<const std::uint8_t>(c.sii_image.data(), 14));
  return c;
}

// Configuration an ordinary master would have written, in the same register format.
void configure(Esc& esc, std::uint16_t station, std::uint32_t logical) {
  std::array<std::uint8_t, 16> bytes{};
  auto frame = [&](std::uint8_t cmd, std::uint16_t ado, std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> pdu(2 + 10 + data.size() + 2, 0);
    const std::size_t len = pdu.size() - 2;
    pdu[0] = static_cast<std::uint8_t>(len);
    pdu[1] = static_cast<std::uint8_t>(0x10 | (len >> 8));
    pdu[2] = cmd;
    pdu[6] = static_cast<std::uint8_t>(ado);
    pdu[7] = static_cast<std::uint8_t>(ado >> 8);
    pdu[8] = static_cast<std::uint8_t>(data.size());
    pdu[9] = static_cast<std::uint8_t>(data.size() >> 8);
    std::copy(data.begin(), data.end(), pdu.begin() + 12);
    esc.process_frame(pdu, FrameTiming{});
  };
  const std::uint8_t st[2] = {static_cast<std::uint8_t>(station),
                              static_cast<std::uint8_t>(station >> 8)};
  frame(0x02, 0x0010, st);  // APWR at position 0 of this ESC alone
  const std::uint8_t sms[32] = {
      0x00, 0x10, 0x20, 0x00, 0x26, 0, 0x01, 0,   // SM0 mailbox out 0x1000, 32 bytes
      0x80, 0x10, 0x20, 0x00, 0x22, 0, 0x01, 0,   // SM1 mailbox in 0x1080
      0x00, 0x11, 0x04, 0x00, 0x64, 0, 0x01, 0,   // SM2 outputs 0x1100, 4 bytes, watchdog
      0x80, 0x11, 0x04, 0x00, 0x20, 0, 0x01, 0};  // SM3 inputs 0x1180
  frame(0x02, 0x0800, sms);
  auto fmmu = [&](int n, std::uint32_t log, std::uint16_t phys, std::uint8_t type,
                  std::uint8_t start_bit, std::uint8_t stop_bit, std::uint8_t phys_bit,
                  std::uint16_t len) {
    bytes = {static_cast<std::uint8_t>(log), static_cast<std::uint8_t>(log >> 8),
             static_cast<std::uint8_t>(log >> 16), static_cast<std::uint8_t>(log >> 24),
             static_cast<std::uint8_t>(len), 0, start_bit, stop_bit,
             static_cast<std::uint8_t>(phys), static_cast<std::uint8_t>(phys >> 8), phys_bit,
             type, 1, 0, 0, 0};
    frame(0x02, static_cast<std::uint16_t>(0x0600 + 16 * n), bytes);
  };
  fmmu(0, logical, 0x1100, 2, 0, 7, 0, 4);
  fmmu(1, logical + 4, 0x1180, 1, 0, 7, 0, 4);
  fmmu(2, logical + 8, 0x080D, 1, 3, 3, 3, 1);  // SM1 "mailbox full" bit
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  VirtualClock clock;
  const EscConfig config = make_config();
  std::unique_ptr<Esc> line[3];
  for (int i = 0; i < 3; ++i) {
    line[i] = std::make_unique<Esc>(config, clock);
    configure(*line[i], static_cast<std::uint16_t>(0x1001 + i), 0x10000u * static_cast<std::uint32_t>(i + 1));
    vdrive::esc::PortLinks links;
    links.port[0] = true;
    links.port[1] = i < 2;
    line[i]->set_links(links);
  }
  std::vector<std::uint8_t> pdu;
  pdu.reserve(2048);
  vdrive::fuzz::for_each_record(data, size, pdu, [&](std::uint8_t flags) {
    if ((flags & 0x01) && pdu.size() >= 2) {
      const std::size_t body = pdu.size() - 2;
      pdu[0] = static_cast<std::uint8_t>(body);
      pdu[1] = static_cast<std::uint8_t>(0x10 | ((body >> 8) & 0x07));
    }
    FrameTiming timing;
    timing.port0_rx = clock.now();
    for (auto& esc : line) {
      if (!esc->process_frame(pdu, timing)) break;
    }
    clock.advance(static_cast<Nanos>(flags >> 1) * 1'000'000);
    for (auto& esc : line) {
      std::array<std::uint8_t, 32> buf{};
      if (esc->pdi_irq() != 0) {
        esc->pdi_read(0x0220, std::span<std::uint8_t>(buf.data(), 4));
        esc->pdi_read(0x0120, std::span<std::uint8_t>(buf.data(), 2));
        esc->pdi_read(0x1000, buf);
        esc->pdi_read(0x1100, std::span<std::uint8_t>(buf.data(), 4));
      }
      esc->pdi_write(0x1180, std::span<const std::uint8_t>(buf.data(), 4));
      if (flags & 0x80) esc->pdi_write(0x1080, buf);
      esc->tick(clock.now());
    }
  });
  return 0;
}
