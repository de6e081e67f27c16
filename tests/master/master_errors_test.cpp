// Master behaviour when the line misbehaves: silence, no slaves, an address that does not stick,
// an EEPROM that stays busy. Driven by a ScriptedLink that plays a minimal slave.
#include <gtest/gtest.h>

#include "master/master.hpp"
#include "master/registers.hpp"
#include "tests/master/scripted_link.hpp"

namespace vdrive::master {
namespace {

using test::ScriptedLink;

constexpr std::size_t kCmd = 16, kAdo = 20, kLen = 22, kData = 26;

std::uint16_t le16(const std::vector<std::uint8_t>& f, std::size_t at) {
  return static_cast<std::uint16_t>(f[at] | (f[at + 1] << 8));
}
void set_wkc(std::vector<std::uint8_t>& f, std::uint16_t wkc) {
  const std::size_t len = le16(f, kLen) & 0x7FF;
  f[kData + len] = static_cast<std::uint8_t>(wkc);
  f[kData + len + 1] = static_cast<std::uint8_t>(wkc >> 8);
}

MasterOptions fast() {
  MasterOptions o;
  o.transport.reply_timeout = 1'000'000;
  o.transport.retries = 1;
  o.sii_busy_timeout = 5'000'000;
  return o;
}

TEST(MasterErrors, SilentLineThrowsWithAUsefulMessage) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto&) { return false; });
  Master m(link, clock, fast());
  try {
    m.scan();
    FAIL() << "scan() must throw";
  } catch (const MasterError& e) {
    EXPECT_NE(std::string(e.what()).find("no reply"), std::string::npos) << e.what();
  }
  EXPECT_EQ(link.sent.size(), 2u) << "one attempt and one retry";
}

TEST(MasterErrors, FrameComesBackUntouchedMeansNoSlaves) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto&) { return true; });  // WKC 0: a loop without slaves
  Master m(link, clock, fast());
  EXPECT_EQ(m.scan(), 0u);
  EXPECT_TRUE(m.slaves().empty());
  EXPECT_EQ(link.sent.size(), 1u) << "nothing to reset or address";
}

// One slave that answers broadcasts and positional writes but whose station address never
// sticks (reads back 0).
TEST(MasterErrors, StationAddressThatDoesNotReadBack) {
  VirtualClock clock;
  ScriptedLink link(clock, [](auto& f) {
    set_wkc(f, 1);
    return true;
  });
  Master m(link, clock, fast());
  try {
    m.scan();
    FAIL() << "scan() must throw";
  } catch (const MasterError& e) {
    EXPECT_NE(std::string(e.what()).find("0x1001"), std::string::npos) << e.what();
  }
}

// A slave whose EEPROM interface reports busy forever.
TEST(MasterErrors, EepromBusyForeverIsASiiError) {
  VirtualClock clock;
  std::uint16_t station = 0;
  ScriptedLink link(clock, [&](auto& f) {
    const auto cmd = static_cast<Command>(f[kCmd]);
    const std::uint16_t ado = le16(f, kAdo);
    if (cmd == Command::APWR && ado == reg::kStationAddress) station = le16(f, kData);
    if (cmd == Command::FPRD && ado == reg::kStationAddress) {
      f[kData] = static_cast<std::uint8_t>(station);
      f[kData + 1] = static_cast<std::uint8_t>(station >> 8);
    }
    if (cmd == Command::FPRD && ado == reg::kEepromControl) f[kData + 1] = 0x80;  // busy
    set_wkc(f, 1);
    return true;
  });
  Master m(link, clock, fast());
  try {
    m.scan();
    FAIL() << "scan() must throw";
  } catch (const MasterError& e) {
    EXPECT_NE(std::string(e.what()).find("busy"), std::string::npos) << e.what();
  }
  EXPECT_GE(clock.now(), fast().sii_busy_timeout) << "it waited the busy timeout, no longer spun forever";
}

}  // namespace
}  // namespace vdrive::master
