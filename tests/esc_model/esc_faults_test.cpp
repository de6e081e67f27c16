// Injected ESC faults (esc_faults.hpp) as a master and the firmware see them through registers:
// working counters, EEPROM status 0x0502, SYNC0/1 events, the process-data watchdog, and the RX
// error counters a frame with a bad FCS leaves behind.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "esc_model/esc_faults.hpp"
#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

constexpr Nanos kMs = 1'000'000;
constexpr std::uint16_t kAckError = 1u << 13, kNotLoaded = 1u << 12, kBusy = 1u << 15;
constexpr std::uint32_t kSync0Event = 0x04, kSync1Event = 0x08, kPdWatchdogEvent = 0x40;

std::vector<std::uint8_t> le(std::uint64_t v, int n) {
  std::vector<std::uint8_t> b;
  for (int i = 0; i < n; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  return b;
}

class EscFaultsTest : public EscTest {
protected:
  void SetUp() override { set_station(); }
  void run_eeprom_command() {
    for (int i = 0; i < 100 && (fprd(0x0502, 2).data[1] & 0x80) != 0; ++i) {
      clock.advance(100'000);
      esc->tick(clock.now());
    }
  }
  std::uint16_t eeprom_status() { return static_cast<std::uint16_t>(fprd(0x0502, 2).data[0] | (fprd(0x0502, 2).data[1] << 8)); }
};

TEST_F(EscFaultsTest, NoFaultsAfterPowerOn) {
  const EscFaults& f = esc->faults();
  EXPECT_FALSE(f.wkc_error || f.sii_error || f.sync_lost || f.pd_watchdog_expired);
}

TEST_F(EscFaultsTest, WkcErrorExecutesNothingAndCountsNoWorkingCounter) {
  ASSERT_EQ(fpwr(0x0F80, {0x11, 0x22}).wkc, 1);
  esc->set_faults({.wkc_error = true});
  EXPECT_TRUE(esc->faults().wkc_error);

  const Result read = fprd(0x0F80, 2);
  EXPECT_EQ(read.wkc, 0);
  EXPECT_EQ(read.data, (std::vector<std::uint8_t>{0, 0})) << "nothing read";
  EXPECT_EQ(fpwr(0x0F80, {0x33, 0x44}).wkc, 0);
  EXPECT_EQ(peek16(0x0F80), 0x2211) << "nothing written";

  // In a line the faulty ESC still forwards and counts auto-increment addresses: the slave
  // behind it answers at its own position, and a broadcast misses exactly one working counter.
  Esc second(default_config(), clock);
  const Result behind = send({esc.get(), &second}, cmd::APRD, Frame::ap(0xFFFF, 0x0000), {0});
  EXPECT_EQ(behind.wkc, 1);
  EXPECT_EQ(behind.adp, 1);
  EXPECT_EQ(send({esc.get(), &second}, cmd::BRD, Frame::ap(0, 0x0000), {0}).wkc, 1);

  esc->set_faults({});
  EXPECT_EQ(send({esc.get(), &second}, cmd::BRD, Frame::ap(0, 0x0000), {0}).wkc, 2);
  EXPECT_EQ(fprd(0x0F80, 2).data, (std::vector<std::uint8_t>{0x11, 0x22}));
}

TEST_F(EscFaultsTest, SiiErrorFailsReadsWithAcknowledgeErrorAndKeepsTheDataRegisters) {
  fpwr(0x0504, le(4, 4));
  fpwr(0x0502, {0x00, 0x01});
  run_eeprom_command();
  ASSERT_EQ(fprd(0x0508, 2).data, u16(0x1234));

  esc->set_faults({.sii_error = true});
  fpwr(0x0504, le(0, 4));
  fpwr(0x0502, {0x00, 0x01});
  run_eeprom_command();
  EXPECT_EQ(eeprom_status() & (kAckError | kBusy), kAckError);
  EXPECT_EQ(fprd(0x0508, 2).data, u16(0x1234)) << "word 0 not loaded";

  esc->set_faults({});
  fpwr(0x0502, {0x00, 0x01});
  run_eeprom_command();
  EXPECT_EQ(eeprom_status() & (kAckError | kBusy), 0);
  EXPECT_EQ(fprd(0x0508, 2).data, u16(0x0C05));
}

TEST_F(EscFaultsTest, SiiErrorReloadAndPowerOnLoadNothing) {
  esc->set_faults({.sii_error = true});
  pdi_write(0x0012, u16(0x5555));
  fpwr(0x0502, {0x00, 0x04});  // reload
  run_eeprom_command();
  EXPECT_EQ(eeprom_status() & (kAckError | kNotLoaded), kAckError | kNotLoaded);
  EXPECT_EQ(peek16(0x0012), 0x5555) << "alias not reloaded";

  esc->reset();
  EXPECT_TRUE(esc->faults().sii_error) << "the board keeps its fault";
  set_station();
  EXPECT_EQ(eeprom_status() & (kAckError | kNotLoaded), kAckError | kNotLoaded);
  EXPECT_EQ(peek16(0x0140), 0) << "PDI control not loaded";
  EXPECT_EQ(peek16(0x0110) & 0x01, 0) << "DL status: PDI not operational";

  esc->set_faults({});
  fpwr(0x0502, {0x00, 0x04});
  run_eeprom_command();
  EXPECT_EQ(eeprom_status() & (kAckError | kNotLoaded), 0);
  EXPECT_EQ(peek16(0x0140), 0x0C05);
  EXPECT_EQ(peek16(0x0110) & 0x01, 0x01);
}

TEST_F(EscFaultsTest, SyncLostDrivesNoSync0OrSync1ButKeepsTheSchedule) {
  fpwr(0x09A0, le(1 * kMs, 4));  // SYNC0 cycle
  fpwr(0x09A4, le(0, 4));        // SYNC1 with SYNC0
  fpwr(0x0990, le(2 * kMs, 8));  // start time
  fpwr(0x0981, {0x07});          // cyclic operation, SYNC0, SYNC1
  esc->set_faults({.sync_lost = true});
  for (int edge = 0; edge < 5; ++edge) {
    const Nanos next = esc->next_deadline();
    ASSERT_LT(next, 10 * kMs);
    clock.set(next);
    esc->tick(next);
    EXPECT_EQ(peek32(0x0220) & (kSync0Event | kSync1Event), 0u) << edge;
    EXPECT_EQ(esc->pdi_irq() & (kSync0Event | kSync1Event), 0u);
    EXPECT_EQ(fprd(0x098E, 2).data, (std::vector<std::uint8_t>{0, 0}));
  }
  // Healed: the next edge on the same grid raises the events again.
  esc->set_faults({});
  const Nanos next = esc->next_deadline();
  clock.set(next);
  esc->tick(next);
  EXPECT_EQ(peek32(0x0220) & (kSync0Event | kSync1Event), kSync0Event | kSync1Event);
}

TEST_F(EscFaultsTest, PdWatchdogExpiredAtOnceAndStaysExpiredWhileSet) {
  constexpr std::uint16_t kOut = 0x1100;
  ASSERT_EQ(fpwr(0x0810, sm_regs(kOut, 2, 0x64)).wkc, 1);  // SM2: buffered, ECAT writes, watchdog
  ASSERT_EQ(fpwr(kOut, {1, 2}).wkc, 1);
  ASSERT_EQ(esc->peek(0x0440) & 0x01, 0x01);

  esc->set_faults({.pd_watchdog_expired = true});
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0);
  EXPECT_EQ(esc->peek(0x0442), 1) << "expiry counted once";
  EXPECT_EQ(peek32(0x0220) & kPdWatchdogEvent, kPdWatchdogEvent);
  EXPECT_EQ(esc->next_deadline(), INT64_MAX) << "no real expiry pending";
  EXPECT_EQ(pdi8(0x0440) & 0x01, 0);  // the firmware reads it: event acknowledged
  EXPECT_EQ(peek32(0x0220) & kPdWatchdogEvent, 0u);

  // The master keeps writing outputs: the watchdog stays expired.
  ASSERT_EQ(fpwr(kOut, {3, 4}).wkc, 1);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0);
  esc->set_faults({.pd_watchdog_expired = true});  // unchanged: not a second expiry
  EXPECT_EQ(esc->peek(0x0442), 1);

  esc->set_faults({});
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0) << "until the next SM2 write";
  ASSERT_EQ(fpwr(kOut, {5, 6}).wkc, 1);
  EXPECT_EQ(esc->peek(0x0440) & 0x01, 0x01);
}

TEST_F(EscFaultsTest, BadFcsIsCountedAsInvalidFrameOrForwardedErrorPerPort) {
  esc->count_rx_error(0, false);
  esc->count_rx_error(1, false);
  esc->count_rx_error(1, false);
  esc->count_rx_error(0, true);
  esc->count_rx_error(1, true);
  esc->count_rx_error(7, false);  // no such port: ignored
  EXPECT_EQ(fprd(0x0300, 12).data, (std::vector<std::uint8_t>{1, 0, 2, 0, 0, 0, 0, 0, 1, 1, 0, 0}));
  for (int i = 0; i < 300; ++i) esc->count_rx_error(0, false);
  EXPECT_EQ(esc->peek(0x0300), 0xFF) << "saturates";
  fpwr(0x0300, {0});  // a master write clears the counters
  EXPECT_EQ(fprd(0x0300, 12).data, std::vector<std::uint8_t>(12, 0));
}

}  // namespace
}  // namespace vdrive::esc::test
