#pragma once
// Test helpers for the ESC: a frame builder (EtherCAT header + datagrams, built byte by byte
// from the ETG.1000.4 layout, independently of ethercat/datagram.hpp), an SII image with a
// valid configuration area, and a fixture holding one ESC on a VirtualClock.
#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "esc_model/sii_eeprom.hpp"

namespace vdrive::esc::test {

namespace cmd {
inline constexpr std::uint8_t NOP = 0x00, APRD = 0x01, APWR = 0x02, APRW = 0x03, FPRD = 0x04,
                              FPWR = 0x05, FPRW = 0x06, BRD = 0x07, BWR = 0x08, BRW = 0x09,
                              LRD = 0x0A, LWR = 0x0B, LRW = 0x0C, ARMW = 0x0D, FRMW = 0x0E;
}

class Frame {
public:
  Frame() : b_{0, 0} {}

  // Adds a datagram; returns its index. `address` is ADP | ADO << 16 (or the logical address).
  std::size_t add(std::uint8_t command, std::uint32_t address, std::vector<std::uint8_t> data,
                  std::uint16_t wkc = 0, std::uint16_t irq = 0) {
    if (!starts_.empty()) b_[starts_.back() + 7] |= 0x80;  // "more" on the previous datagram
    starts_.push_back(b_.size());
    lengths_.push_back(data.size());
    b_.push_back(command);
    b_.push_back(0x5A);  // index
    for (int i = 0; i < 4; ++i) b_.push_back(static_cast<std::uint8_t>(address >> (8 * i)));
    b_.push_back(static_cast<std::uint8_t>(data.size()));
    b_.push_back(static_cast<std::uint8_t>((data.size() >> 8) & 0x07));
    b_.push_back(static_cast<std::uint8_t>(irq));
    b_.push_back(static_cast<std::uint8_t>(irq >> 8));
    b_.insert(b_.end(), data.begin(), data.end());
    b_.push_back(static_cast<std::uint8_t>(wkc));
    b_.push_back(static_cast<std::uint8_t>(wkc >> 8));
    const std::size_t len = b_.size() - 2;
    b_[0] = static_cast<std::uint8_t>(len);
    b_[1] = static_cast<std::uint8_t>(0x10 | ((len >> 8) & 0x07));  // type 1
    return starts_.size() - 1;
  }
  static std::uint32_t ap(std::uint16_t adp, std::uint16_t ado) {
    return adp | (static_cast<std::uint32_t>(ado) << 16);
  }

  std::vector<std::uint8_t> data(std::size_t i) const {
    const auto first = b_.begin() + static_cast<std::ptrdiff_t>(starts_[i] + 10);
    return {first, first + static_cast<std::ptrdiff_t>(lengths_[i])};
  }
  std::uint16_t wkc(std::size_t i) const { return le16(starts_[i] + 10 + lengths_[i]); }
  std::uint16_t adp(std::size_t i) const { return le16(starts_[i] + 2); }
  std::uint16_t irq(std::size_t i) const { return le16(starts_[i] + 8); }
  std::uint16_t len_field(std::size_t i) const { return le16(starts_[i] + 6); }

  std::vector<std::uint8_t>& bytes() { return b_; }
  std::span<std::uint8_t> pdu() { return b_; }

private:
  std::uint16_t le16(std::size_t at) const {
    return static_cast<std::uint16_t>(b_[at] | (b_[at + 1] << 8));
  }
  std::vector<std::uint8_t> b_;
  std::vector<std::size_t> starts_;
  std::vector<std::size_t> lengths_;
};

// 2 KiB EEPROM: words 0-7 ESC configuration area with valid CRC, then zeros.
inline std::vector<std::uint8_t> sii_image(std::uint16_t alias = 0x1234,
                                           std::uint16_t pdi_control = 0x0C05) {
  std::vector<std::uint8_t> img(2048, 0);
  auto put = [&](std::size_t word, std::uint16_t v) {
    img[2 * word] = static_cast<std::uint8_t>(v);
    img[2 * word + 1] = static_cast<std::uint8_t>(v >> 8);
  };
  put(0, pdi_control);
  put(1, 0x6603);
  put(2, 0x0064);
  put(3, 0x0000);
  put(4, alias);
  img[14] = sii_config_crc(std::span<const std::uint8_t>(img.data(), 14));
  return img;
}

inline EscConfig default_config() {
  EscConfig c;
  c.sii_image = sii_image();
  return c;
}

struct Result {
  std::vector<std::uint8_t> data;
  std::uint16_t wkc = 0;
  std::uint16_t adp = 0;
  bool passed = false;
};

// Sends one datagram through a line of ESCs.
inline Result send(const std::vector<Esc*>& line, std::uint8_t command, std::uint32_t address,
                   std::vector<std::uint8_t> data, Nanos t = 0) {
  Frame f;
  f.add(command, address, std::move(data));
  Result r;
  r.passed = true;
  FrameTiming timing;
  timing.port0_rx = t;
  for (Esc* e : line) r.passed = e->process_frame(f.pdu(), timing) && r.passed;
  r.data = f.data(0);
  r.wkc = f.wkc(0);
  r.adp = f.adp(0);
  return r;
}

class EscTest : public ::testing::Test {
protected:
  EscTest() : esc(std::make_unique<Esc>(default_config(), clock)) {}

  Result fprd(std::uint16_t ado, std::size_t len, std::uint16_t station = 0x1001) {
    return send({esc.get()}, cmd::FPRD, Frame::ap(station, ado), std::vector<std::uint8_t>(len, 0),
                clock.now());
  }
  Result fpwr(std::uint16_t ado, std::vector<std::uint8_t> d, std::uint16_t station = 0x1001) {
    return send({esc.get()}, cmd::FPWR, Frame::ap(station, ado), std::move(d), clock.now());
  }
  Result aprd(std::uint16_t ado, std::size_t len) {
    return send({esc.get()}, cmd::APRD, Frame::ap(0, ado), std::vector<std::uint8_t>(len, 0),
                clock.now());
  }
  Result apwr(std::uint16_t ado, std::vector<std::uint8_t> d) {
    return send({esc.get()}, cmd::APWR, Frame::ap(0, ado), std::move(d), clock.now());
  }
  // Configures station address 0x1001 through auto-increment addressing.
  void set_station(std::uint16_t station = 0x1001) {
    apwr(0x0010, {static_cast<std::uint8_t>(station), static_cast<std::uint8_t>(station >> 8)});
  }
  std::uint8_t pdi8(std::uint16_t a) {
    std::uint8_t v = 0;
    esc->pdi_read(a, std::span<std::uint8_t>(&v, 1));
    return v;
  }
  std::uint16_t pdi16(std::uint16_t a) {
    std::uint8_t v[2] = {};
    esc->pdi_read(a, v);
    return static_cast<std::uint16_t>(v[0] | (v[1] << 8));
  }
  std::uint32_t pdi32(std::uint16_t a) {
    std::uint8_t v[4] = {};
    esc->pdi_read(a, v);
    return static_cast<std::uint32_t>(v[0] | (v[1] << 8) | (v[2] << 16) |
                                      (static_cast<std::uint32_t>(v[3]) << 24));
  }
  void pdi_write(std::uint16_t a, std::vector<std::uint8_t> d) { esc->pdi_write(a, d); }
  std::uint16_t peek16(std::uint16_t a) const {
    return static_cast<std::uint16_t>(esc->peek(a) | (esc->peek(a + 1) << 8));
  }
  std::uint32_t peek32(std::uint16_t a) const {
    return peek16(a) | (static_cast<std::uint32_t>(peek16(static_cast<std::uint16_t>(a + 2))) << 16);
  }

  // SyncManager n registers: start, length, control, activate.
  static std::vector<std::uint8_t> sm_regs(std::uint16_t start, std::uint16_t len,
                                           std::uint8_t control, std::uint8_t activate = 0x01) {
    return {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
            static_cast<std::uint8_t>(len), static_cast<std::uint8_t>(len >> 8), control, 0,
            activate, 0};
  }

  VirtualClock clock;
  std::unique_ptr<Esc> esc;
};

inline std::vector<std::uint8_t> u16(std::uint16_t v) {
  return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)};
}

}  // namespace vdrive::esc::test
