// The ESC's wiring of DcUnit and SiiEeprom: register windows, receive-time latch, SYNC events
// into the AL event register, EEPROM reload into the ESC registers.
#include <gtest/gtest.h>

#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

constexpr Nanos kMs = 1'000'000;

std::vector<std::uint8_t> le(std::uint64_t v, int n) {
  std::vector<std::uint8_t> b;
  for (int i = 0; i < n; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  return b;
}

class EscDcTest : public EscTest {
protected:
  void SetUp() override { set_station(); }
};

TEST_F(EscDcTest, FrameWritingReceiveTimeRegisterLatchesPortTimes) {
  Result r = send({esc.get()}, cmd::BWR, Frame::ap(0, 0x0900), {0, 0, 0, 0}, 12345);
  EXPECT_EQ(r.wkc, 1);
  EXPECT_EQ(fprd(0x0900, 4).data, le(12345, 4));
}

TEST_F(EscDcTest, ReadingReceiveTimeRegisterDoesNotLatch) {
  send({esc.get()}, cmd::BWR, Frame::ap(0, 0x0900), {0, 0, 0, 0}, 500);
  send({esc.get()}, cmd::BRD, Frame::ap(0, 0x0900), {0, 0, 0, 0}, 900);
  EXPECT_EQ(fprd(0x0900, 4).data, le(500, 4));
}

TEST_F(EscDcTest, Sync0PulseRaisesAlEventClearedByReadingSync0Status) {
  fpwr(0x09A0, le(1 * kMs, 4));  // SYNC0 cycle
  fpwr(0x0990, le(2 * kMs, 8));  // start time (system time)
  fpwr(0x0981, {0x03});          // cyclic operation + SYNC0
  const Nanos first = esc->next_deadline();
  ASSERT_GT(first, 0);
  ASSERT_LE(first, 2 * kMs);
  clock.set(first);
  esc->tick(first);
  EXPECT_EQ(peek32(0x0220) & 0x04u, 0x04u);
  EXPECT_EQ(esc->pdi_irq() & 0x04u, 0x04u);
  pdi8(0x098E);
  EXPECT_EQ(peek32(0x0220) & 0x04u, 0u);
  EXPECT_GT(esc->next_deadline(), first);
}

TEST_F(EscDcTest, EepromWindowDelegatesToSii) {
  // Read EEPROM word 4 (alias) through the ECAT EEPROM interface: address, then read command.
  fpwr(0x0504, le(4, 4));
  fpwr(0x0502, {0x00, 0x01});
  for (int i = 0; i < 100 && (fprd(0x0502, 2).data[1] & 0x80) != 0; ++i) {
    clock.advance(100'000);
    esc->tick(clock.now());
  }
  EXPECT_EQ(fprd(0x0508, 2).data, u16(0x1234));
}

TEST_F(EscDcTest, EepromReloadCommandCopiesConfigurationAreaAgain) {
  pdi_write(0x0012, u16(0x5555));
  ASSERT_EQ(peek16(0x0012), 0x5555);
  fpwr(0x0502, {0x00, 0x04});  // reload command
  for (int i = 0; i < 100 && (fprd(0x0502, 2).data[1] & 0x80) != 0; ++i) {
    clock.advance(100'000);
    esc->tick(clock.now());
  }
  EXPECT_EQ(peek16(0x0012), 0x1234);
  EXPECT_EQ(peek16(0x0140), 0x0C05);
  EXPECT_EQ(peek16(0x0110) & 0x01, 0x01);
}

}  // namespace
}  // namespace vdrive::esc::test
