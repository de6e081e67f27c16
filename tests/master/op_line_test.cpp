// The master's way to Op on a line of real vdrive slaves in virtual time: process data layout,
// SM2/SM3 and FMMUs in the ESCs, DC delays/offsets against the segment's hop delay, SYNC0 start
// and cycle, and cyclic LRW with exact working counters.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "master/cyclic_task.hpp"
#include "master/dc.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "master/registers.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::master {
namespace {

class OpLine : public ::testing::Test {
protected:
  const std::vector<std::string> products{"a6b", "ds5c1", "ds1000a"};
  test::VirtualLine line{products};
  Master master{line, line.clock()};

  void SetUp() override {
    ASSERT_EQ(master.scan(), 3u);
    master.set_mailbox_timeout(20'000'000);
  }
  std::uint16_t esc_u16(std::size_t slave, std::uint16_t address) {
    auto& esc = line.network().esc(slave);
    return static_cast<std::uint16_t>(esc.peek(address) | (esc.peek(address + 1) << 8));
  }
  std::uint32_t esc_u32(std::size_t slave, std::uint16_t address) {
    return esc_u16(slave, address) | (static_cast<std::uint32_t>(esc_u16(slave, address + 2)) << 16);
  }
  std::uint64_t system_time(std::size_t slave) {
    std::array<std::uint8_t, 8> t{};
    EXPECT_EQ(master.transport().fprd(master.slaves()[slave].station, reg::kDcSystemTime, t), 1);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(t[i]) << (8 * i);
    return v;
  }
};

TEST_F(OpLine, ProcessDataLayoutIsWrittenToSmsAndFmmus) {
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  std::vector<std::string> notes;
  const ProcessImageLayout layout = configure_process_data(master, &notes);
  std::uint32_t outputs = 0, inputs = 0;
  std::uint16_t wkc = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(products[i]);
    const SlaveProcessData& pd = master.slaves()[i].process_data;
    // The manuals' default mapping (profile SM2/SM3 lengths) is what the drive assigns at power-on.
    const auto profile = profile::load_profile(products[i]);
    ASSERT_GE(profile.sync_managers.size(), 4u);
    EXPECT_EQ(pd.output_bytes, profile.sync_managers[2].length) << "default RxPDO mapping";
    EXPECT_EQ(pd.input_bytes, profile.sync_managers[3].length) << "default TxPDO mapping";
    // SM2/SM3 in the ESC: start from the SII, length = the mapped bytes, enabled.
    EXPECT_EQ(esc_u16(i, 0x0810), pd.sm2_start);
    EXPECT_EQ(esc_u16(i, 0x0812), pd.output_bytes);
    EXPECT_EQ(line.network().esc(i).peek(0x0816) & 1, 1);
    EXPECT_EQ(esc_u16(i, 0x0818), pd.sm3_start);
    EXPECT_EQ(esc_u16(i, 0x081A), pd.input_bytes);
    // FMMU0 writes outputs at the slave's logical address, FMMU1 reads inputs.
    EXPECT_EQ(esc_u32(i, 0x0600), pd.output_logical);
    EXPECT_EQ(esc_u16(i, 0x0604), pd.output_bytes);
    EXPECT_EQ(esc_u16(i, 0x0608), pd.sm2_start);
    EXPECT_EQ(line.network().esc(i).peek(0x060B), 2);
    EXPECT_EQ(esc_u32(i, 0x0610), pd.input_logical);
    EXPECT_EQ(line.network().esc(i).peek(0x061B), 1);
    EXPECT_EQ(pd.output_logical, outputs) << "outputs packed from logical 0";
    outputs += pd.output_bytes;
    inputs += pd.input_bytes;
    wkc = static_cast<std::uint16_t>(wkc + (pd.output_bytes ? 2 : 0) + (pd.input_bytes ? 1 : 0));
  }
  EXPECT_EQ(master.slaves()[0].process_data.input_logical, outputs) << "inputs after all outputs";
  EXPECT_EQ(layout.output_bytes, outputs);
  EXPECT_EQ(layout.input_bytes, inputs);
  EXPECT_EQ(layout.expected_wkc, wkc);
}

TEST_F(OpLine, DcDelaysFollowTheHopDelayAndSystemTimesAgree) {
  const DcResult dc = configure_dc(master, DcOptions{200});
  ASSERT_EQ(dc.dc_slaves, 3u);
  EXPECT_EQ(dc.reference_station, 0x1001);
  // The segment adds hop_delay per slave and direction: slave k is k hops behind the first.
  const Nanos hop = line.network().segment().hop_delay();
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(static_cast<double>(master.slaves()[i].dc_delay), static_cast<double>(i * hop), 100.0) << i;
  }
  // One frame reads all three system times; slave k sees it k hops later, so its reading is
  // larger by its delay when the clocks agree.
  Frame frame;
  std::array<int, 3> slot{};
  for (std::size_t i = 0; i < 3; ++i) {
    slot[i] = frame.add(Command::FPRD, static_cast<std::uint8_t>(i), station_address(master.slaves()[i].station, reg::kDcSystemTime), 8);
  }
  ASSERT_TRUE(master.transport().transceive(frame));
  auto value = [&](std::size_t i) {
    std::uint64_t v = 0;
    const auto d = frame.data(static_cast<std::size_t>(slot[i]));
    for (int b = 0; b < 8; ++b) v |= static_cast<std::uint64_t>(d[b]) << (8 * b);
    return static_cast<std::int64_t>(v);
  };
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_NEAR(static_cast<double>(value(i) - value(0)), static_cast<double>(master.slaves()[i].dc_delay), 100.0) << i;
  }
}

TEST_F(OpLine, Sync0StartAndCycleAreProgrammed) {
  configure_dc(master, DcOptions{100});
  const std::uint64_t start = activate_sync0(master, 1'000'000, 0, 50'000'000);
  EXPECT_EQ(start % 1'000'000, 0u) << "a whole number of cycles";
  EXPECT_GT(start, system_time(0) + 40'000'000);
  for (std::size_t i = 0; i < 3; ++i) {
    std::array<std::uint8_t, 13> sync{};  // 0x0990 start (8) .. 0x09A0 cycle (4)
    ASSERT_EQ(master.transport().fprd(master.slaves()[i].station, 0x0990, std::span(sync.data(), 8)), 1);
    std::uint64_t s = 0;
    for (int b = 0; b < 8; ++b) s |= static_cast<std::uint64_t>(sync[b]) << (8 * b);
    EXPECT_EQ(s, start);
    EXPECT_EQ(master.transport().fprd_value<std::uint32_t>(master.slaves()[i].station, 0x09A0), 1'000'000u);
    EXPECT_EQ(master.transport().fprd_value<std::uint8_t>(master.slaves()[i].station, 0x0981), 0x03);
  }
}

TEST_F(OpLine, ThreeDrivesReachOpWithDcAndExactWorkingCounters) {
  OpRunOptions options;
  options.cycle = 1'000'000;
  options.cycles = 500;
  options.drift_frames = 200;
  options.mailbox_timeout = 20'000'000;
  const OpRunResult result = run_to_op(master, options);
  for (const auto& n : result.notes) std::printf("note: %s\n", n.c_str());
  ASSERT_TRUE(result.reached_op) << result.error;
  EXPECT_EQ(result.stats.cycles, 500u);
  EXPECT_EQ(result.stats.wrong_wkc, 0u);
  EXPECT_EQ(result.stats.lost_frames, 0u);
  EXPECT_EQ(result.left_op, 0u);
  // What the ESCs counted in the last cycle: +2 per slave with outputs, +1 with inputs.
  std::uint16_t expected = 0;
  for (const Slave& s : master.slaves()) expected = static_cast<std::uint16_t>(expected + s.process_data.expected_wkc());
  EXPECT_EQ(result.stats.last_wkc, expected);
  EXPECT_GE(expected, 6) << "at least outputs and inputs of two drives";
  EXPECT_TRUE(result.ok());
}

// Oscillators that start apart and run at different rates: the offsets bring the system times
// together, and the FRMW of 0x0910 in every cycle keeps them together.
TEST(OpLineDc, DriftingClocksStayWithin100NsWhileCycling) {
  network::NetworkOptions options;
  options.dc_models = {{20.0, 5'000'000'000}, {-50.0, 123'456}, {35.0, 900'000'000'000}};
  test::VirtualLine line({"a6b", "ds5c1", "ds1000a"}, options);
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  master.set_mailbox_timeout(20'000'000);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  const ProcessImageLayout layout = configure_process_data(master);
  const DcResult dc = configure_dc(master, DcOptions{3000});
  ASSERT_EQ(dc.dc_slaves, 3u);
  CyclicTask task(master.transport(), layout, 3, 1'000'000, dc.reference_station);
  task.run(2000);  // 2 s: 70 ppm apart would be 140 us without compensation
  EXPECT_EQ(task.stats().wrong_wkc, 0u);
  Frame frame;
  for (std::size_t i = 0; i < 3; ++i) {
    frame.add(Command::FPRD, static_cast<std::uint8_t>(0x40 + i), station_address(master.slaves()[i].station, reg::kDcSystemTime), 8);
  }
  ASSERT_TRUE(master.transport().transceive(frame));
  auto value = [&](std::size_t i) {
    std::uint64_t v = 0;
    for (int b = 0; b < 8; ++b) v |= static_cast<std::uint64_t>(frame.data(i)[b]) << (8 * b);
    return static_cast<std::int64_t>(v);
  };
  for (std::size_t i = 1; i < 3; ++i) {
    EXPECT_NEAR(static_cast<double>(value(i) - value(0) - master.slaves()[i].dc_delay), 0.0, 100.0) << "slave " << i;
  }
}

TEST_F(OpLine, CyclicTaskCountsAWrongWorkingCounter) {
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  ProcessImageLayout layout = configure_process_data(master);
  // One slave more than there is, with one output byte in the image: the LRW expects +2 more.
  layout.slaves.push_back({layout.logical_start, 1, 0, 0});
  CyclicTask task(master.transport(), layout, 3, 1'000'000);
  task.run(10);
  EXPECT_EQ(task.stats().cycles, 10u);
  EXPECT_EQ(task.stats().wrong_wkc, 10u);
}

TEST_F(OpLine, CyclicTaskCallsBackAndRunsAtTheCycleTime) {
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  const ProcessImageLayout layout = configure_process_data(master);
  CyclicTask task(master.transport(), layout, 3, 500'000);
  int outs = 0, ins = 0;
  task.on_outputs([&](std::span<std::uint8_t> image) {
    ++outs;
    EXPECT_EQ(image.size(), layout.size());
  });
  task.on_inputs([&](std::span<std::uint8_t>) { ++ins; });
  const Nanos start = line.clock().now();
  task.run(100);
  EXPECT_EQ(outs, 100);
  EXPECT_EQ(ins, 100);
  EXPECT_NEAR(static_cast<double>(line.clock().now() - start), 100 * 500'000.0, 500'000.0);
  EXPECT_EQ(task.stats().al_wkc, 3);
  EXPECT_EQ(task.stats().al_status & 0x0F, 0x02) << "BRD of AL status: all in Pre-Op";
}

}  // namespace
}  // namespace vdrive::master
