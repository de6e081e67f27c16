// EtherCAT errors as the drive's alarms, on the whole firmware and a real ESC: an A6B enabled in
// csp loses its outputs, the SM watchdog expires (AL status code 001Bh, L32567-L32645), and the
// drive shows Err80.4 (603Fh FF50h) in Fault. The master acknowledges the AL error, returns to Op
// and resets the fault with 6040h bit 7 (L34013-L34017); that a reset before the acknowledge is
// refused is tested on the engine (tests/drive/engine_alarms_test.cpp), since outputs only reach
// 6040h in Op.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "tests/firmware/pdo_test_bench.hpp"
#include "vdrive/drive/drive_engine.hpp"

namespace vdrive::firmware {
namespace {

constexpr std::uint16_t kPreOp = 0x0002, kSafeOp = 0x0004, kOp = 0x0008, kAck = 0x0010;
constexpr std::uint16_t kA6bOut = 9, kA6bIn = 23;  // factory mapping 1 (L7346-L7374)

class A6bAlErrorAlarm : public ::testing::Test {
protected:
  A6bAlErrorAlarm() : b("a6b"), lrw(test::WireBench::frame(test::kLrw, test::kLogicalOutputs, kA6bOut + kA6bIn)) {}

  void request(std::uint16_t control) {
    b.write_u16(0x0120, control);
    run_for(1'000'000, false);
  }
  std::uint16_t al_status() { return b.read_u16(0x0130); }

  // 6040h (bytes 0-1), 6060h (2), 607Ah (3-6) of RxPDO 1600h.
  void outputs(std::uint16_t controlword, std::int8_t mode, std::int32_t target) {
    auto out = test::WireBench::data_of(lrw);
    out[0] = static_cast<std::uint8_t>(controlword);
    out[1] = static_cast<std::uint8_t>(controlword >> 8);
    out[2] = static_cast<std::uint8_t>(mode);
    for (int i = 0; i < 4; ++i) out[3 + i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(target) >> (8 * i));
  }

  // `duration` of time in control steps; with `cyclic`, one LRW frame every 1 ms.
  void run_for(Nanos duration, bool cyclic) {
    const Nanos end = b.clock.now() + duration;
    while (b.clock.now() < end) {
      const Nanos step = std::min<Nanos>(b.fw.next_deadline() - b.clock.now(), 125'000);
      b.advance(std::max<Nanos>(step, 1));
      b.fw.tick(b.clock.now());
      if (cyclic && b.clock.now() % 1'000'000 < 125'000) b.run(lrw);
    }
  }

  drive::DriveEngine& drive() { return *b.fw.drive(); }

  test::PdoBench b;
  std::vector<std::uint8_t> lrw;
};

TEST_F(A6bAlErrorAlarm, WatchdogExpiryIsErr80_4AndClearsAfterAcknowledgeOpAndFaultReset) {
  b.mailbox_layout();
  request(kPreOp);
  b.process_data_layout(kA6bOut, kA6bIn);
  request(kSafeOp);
  ASSERT_EQ(al_status() & 0x1F, kSafeOp);
  const auto here = static_cast<std::int32_t>(drive().sample().position);
  outputs(0x0000, 8, here);
  b.run(lrw);
  request(kOp);
  ASSERT_EQ(al_status() & 0x1F, kOp);
  for (const std::uint16_t cw : {0x0006, 0x0007, 0x000F}) {
    outputs(cw, 8, here);
    run_for(20'000'000, true);
  }
  ASSERT_EQ(drive().state(), drive::PdsState::OperationEnabled);

  run_for(300'000'000, false);  // the master stops: the 100 ms SM watchdog expires
  EXPECT_EQ(al_status(), 0x0014) << "Safe-Op with the error flag";
  EXPECT_EQ(b.read_u16(0x0134), 0x001B);
  EXPECT_EQ(drive().alarms().error_code(), 0xFF50) << "Err80.4 (L32567-L32645)";
  EXPECT_EQ(drive().alarms().newest()->code, "80.4");
  EXPECT_EQ(drive().state(), drive::PdsState::Fault);

  // Acknowledge (Safe-Op + ack), outputs again, Op, then the fault-reset edge.
  request(kSafeOp | kAck);
  EXPECT_EQ(al_status(), 0x0004);
  outputs(0x0000, 8, here);
  run_for(5'000'000, true);
  request(kOp);
  ASSERT_EQ(al_status() & 0x1F, kOp);
  run_for(5'000'000, true);
  EXPECT_EQ(drive().state(), drive::PdsState::Fault) << "the alarm stays until it is reset";
  outputs(0x0080, 8, here);
  run_for(5'000'000, true);
  EXPECT_EQ(drive().state(), drive::PdsState::SwitchOnDisabled);
  EXPECT_EQ(drive().alarms().error_code(), 0);
}

}  // namespace
}  // namespace vdrive::firmware
