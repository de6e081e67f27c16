// ESC and cable faults on a line of real drives, as the master sees them: the ESC only stops doing
// what the silicon would (SYNC0 pulses, the SM watchdog, working counters), and the firmware
// reports its own AL status code (A6B lost sync 002Ch after 3742h misses, SM watchdog 001Bh);
// a cable break after slave 1 and its repair show in the broadcast working counter.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "esc_model/esc_faults.hpp"
#include "ethercat/registers.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"

namespace vdrive::master {
namespace {

constexpr Nanos kMs = 1'000'000;
constexpr std::uint16_t kAlErrorFlag = 0x10;

class EscFaultsInOp : public ::testing::Test {
protected:
  test::VirtualLine line{{"a6b", "ds5c1"}};
  Master master{line, line.clock()};

  void SetUp() override {
    ASSERT_EQ(master.scan(), 2u);
    master.set_mailbox_timeout(20 * kMs);
  }
  std::uint16_t esc_u16(std::size_t slave, std::uint16_t address) {
    esc::Esc& e = line.network().esc(slave);
    return static_cast<std::uint16_t>(e.peek(address) | (e.peek(static_cast<std::uint16_t>(address + 1)) << 8));
  }
  // Runs to Op with DC; after `healthy` cycles in Op `inject` runs, then the cycles go on until
  // slave `watched` shows the AL error flag (or the run ends).
  // Op with DC at 1 ms for 600 cycles, staying in Op at the end.
  static OpRunOptions options() {
    OpRunOptions o;
    o.cycle = 1 * kMs;
    o.cycles = 600;
    o.drift_frames = 200;
    o.mailbox_timeout = 20 * kMs;
    o.back_to_init = false;
    return o;
  }
  OpRunResult run(std::size_t watched, const std::function<void()>& inject, int healthy = 100) {
    OpRunOptions o = options();
    // A6B Err80.7: lost sync after 3 consecutive missing SYNC0 (3742h bits 3-0; 0 = never).
    o.preop = [](Master& m) { m.sdo(0).download_value<std::int16_t>(0x3742, 0, 3); };
    int cycles = 0;
    o.done = [&, watched] {
      if (++cycles == healthy) inject();
      return cycles > healthy && (esc_u16(watched, ecat::reg::kAlStatus) & kAlErrorFlag) != 0;
    };
    return run_to_op(master, o);
  }
};

TEST_F(EscFaultsInOp, SyncLostMakesTheA6bReportLostSync002C) {
  const OpRunResult r = run(0, [&] { line.network().esc(0).set_faults({.sync_lost = true}); });
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_EQ(esc_u16(0, ecat::reg::kAlStatus), 0x0014) << "Safe-Op with the error flag";
  EXPECT_EQ(esc_u16(0, ecat::reg::kAlStatusCode), 0x002C) << "A6B Err80.7 (profile al_codes.sync_error)";
  EXPECT_EQ(esc_u16(1, ecat::reg::kAlStatus), 0x0008) << "the other drive keeps its SYNC0 and Op";
  EXPECT_GT(r.left_op, 0u);
}

TEST_F(EscFaultsInOp, ExpiredProcessDataWatchdogIsAlStatusCode001B) {
  const OpRunResult r = run(1, [&] { line.network().esc(1).set_faults({.pd_watchdog_expired = true}); });
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_EQ(esc_u16(1, ecat::reg::kAlStatus), 0x0014) << "Safe-Op with the error flag";
  EXPECT_EQ(esc_u16(1, ecat::reg::kAlStatusCode), 0x001B);
  EXPECT_EQ(line.network().esc(1).peek(ecat::reg::kWatchdogStatusProcessData) & 0x01, 0)
      << "0x0440 reads expired although the master kept writing SM2";
  EXPECT_EQ(esc_u16(0, ecat::reg::kAlStatus), 0x0008);
}

TEST_F(EscFaultsInOp, WkcErrorCostsTheCyclicFrameItsShareOfTheWorkingCounter) {
  const OpRunResult r = run(0, [&] { line.network().esc(1).set_faults({.wkc_error = true}); });
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_GT(r.stats.wrong_wkc, 0u);
  // The cyclic LRW still counts slave 1's outputs and inputs; slave 2 executes nothing.
  EXPECT_EQ(r.stats.last_wkc, master.slaves()[0].process_data.expected_wkc());
}

TEST_F(EscFaultsInOp, WithRecoverTheMasterTakesTheLineBackToOpOnceTheCauseIsGone) {
  OpRunOptions o = options();
  o.recover = true;
  int cycles = 0;
  o.done = [&] {
    ++cycles;
    if (cycles == 100) line.network().esc(1).set_faults({.pd_watchdog_expired = true});
    if (cycles == 200) line.network().esc(1).set_faults({});  // the master retried meanwhile, refused
    return false;
  };
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_GE(r.recoveries, 1u);
  EXPECT_GT(r.left_op, 0u) << "the watchdog took slave 2 out of Op";
  EXPECT_EQ(esc_u16(0, ecat::reg::kAlStatus), 0x0008);
  EXPECT_EQ(esc_u16(1, ecat::reg::kAlStatus), 0x0008) << "acknowledged and back in Op";
}

// How long the line was out is measured, the bound is checked, and the status callback follows
// the counters in the cycles (what `vdrive-master op --recover --status-every-ms` prints).
TEST_F(EscFaultsInOp, TheTimeOutOfOpIsMeasuredAndBoundedAndTheStatusFollowsIt) {
  OpRunOptions o = options();
  o.recover = true;
  o.recover_bound = 50 * kMs;
  o.status_every = 100 * kMs;
  std::vector<OpStatus> statuses;
  o.status = [&](const OpStatus& s) { statuses.push_back(s); };
  int cycles = 0;
  o.done = [&] {
    ++cycles;
    // Slave 2 executes nothing, the BRD of the AL status too: the line is out until it is lifted
    // (and its SM watchdog expires meanwhile, which the acknowledgement clears).
    if (cycles == 100) line.network().esc(1).set_faults({.wkc_error = true});
    if (cycles == 300) line.network().esc(1).set_faults({});
    return false;
  };
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_GE(r.longest_out_of_op, 150 * kMs) << "out from about cycle 100 until the fault was lifted at 300";
  EXPECT_LE(r.longest_out_of_op, 260 * kMs);
  EXPECT_EQ(r.overdue, 1u) << "beyond the 50 ms bound once";
  EXPECT_FALSE(r.recovered());
  ASSERT_EQ(statuses.size(), 6u) << "every 100 of the 600 cycles";
  EXPECT_EQ(statuses[0].in_op, 100 * kMs);
  EXPECT_TRUE(statuses[0].all_in_op);
  EXPECT_FALSE(statuses[1].all_in_op) << "at cycle 200 slave 2 is out";
  EXPECT_GT(statuses[2].left_op, 0u);
  EXPECT_TRUE(statuses[5].all_in_op) << "back by cycle 600";
  EXPECT_EQ(statuses[5].left_op, r.left_op);
}

TEST_F(EscFaultsInOp, WithoutRecoverTheLineStaysOutOfOp) {
  const OpRunResult r = run(1, [&] { line.network().esc(1).set_faults({.pd_watchdog_expired = true}); });
  ASSERT_TRUE(r.reached_op) << r.error;
  line.network().esc(1).set_faults({});
  EXPECT_EQ(r.recoveries, 0u);
  EXPECT_EQ(esc_u16(1, ecat::reg::kAlStatus), 0x0014);
}

TEST(CableFaultOnLine, BreakAfterSlave1AndItsRepairShowInTheBroadcastWorkingCounter) {
  test::VirtualLine line({"a6b", "ds5c1", "ds1000a"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  std::array<std::uint8_t, 2> type{};
  EXPECT_EQ(master.transport().brd(ecat::reg::kType, type), 3);
  line.network().segment().set_cable(0, false);  // between slave 1 and slave 2
  EXPECT_EQ(master.transport().brd(ecat::reg::kType, type), 1) << "slave 1 closes its port 1 and turns the frame";
  // Slave 1 reports port 1 without link (DL status 0x0110 bit 5) and counts the lost link.
  const auto dl = master.transport().fprd_value<std::uint16_t>(master.slaves()[0].station, ecat::reg::kDlStatus);
  ASSERT_TRUE(dl.has_value());
  EXPECT_EQ(*dl & 0x0030, 0x0010);
  EXPECT_EQ(master.transport().fprd_value<std::uint8_t>(master.slaves()[0].station, ecat::reg::kLostLinkCounter + 1), 1);
  EXPECT_FALSE(master.transport().fprd_value<std::uint16_t>(master.slaves()[1].station, ecat::reg::kDlStatus))
      << "slave 2 is out of reach";
  line.network().segment().set_cable(0, true);
  EXPECT_EQ(master.transport().brd(ecat::reg::kType, type), 3);
  EXPECT_TRUE(master.transport().fprd_value<std::uint16_t>(master.slaves()[1].station, ecat::reg::kDlStatus));
}

}  // namespace
}  // namespace vdrive::master
