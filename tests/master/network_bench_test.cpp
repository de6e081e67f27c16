// The bench of tests/products/networks/bench.yaml, served as `vdrive run --network` serves it: a
// coupler with a digital input and output terminal on its E-bus port (3) and an ESI drive on its
// second port (1), a loopback wire from output channel 1 to input channel 1. The project master
// scans the tree in the order a frame visits it, takes it to Op with DC at 1 ms, runs a csp sine on
// the drive and reads back through the input terminal what it writes to the output terminal.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "master/cia402_program.hpp"
#include "tests/master/csp_sine_run.hpp"
#include "master/dc.hpp"
#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/machine/network_file.hpp"

namespace vdrive::master {
namespace {

struct Bench {
  machine::NetworkFile file = machine::load_network_file(std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/networks/bench.yaml");
  std::vector<std::string> devices() const {
    std::vector<std::string> d;
    for (const machine::NetworkSlave& s : file.slaves) d.push_back(s.device);
    return d;
  }
  network::NetworkOptions options() const { return machine::network_options(file); }
};

TEST(NetworkBench, TheMasterScansTheTreeInFrameOrder) {
  const Bench bench;
  test::VirtualLine line(bench.devices(), bench.options());
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 4u);
  // Coupler, its E-bus terminals (port 3 first), then the drive behind port 1.
  EXPECT_EQ(master.slaves()[0].info.product_code, 0x044C2C52u);
  EXPECT_EQ(master.slaves()[1].info.product_code, 0x03F03052u);
  EXPECT_EQ(master.slaves()[2].info.product_code, 0x07D83052u);
  EXPECT_EQ(master.slaves()[3].info.product_code, 0x00000402u);
  EXPECT_EQ(master.slaves()[3].info.alias, 0x0102);
  // The tree as the receive times show it: DI on the coupler's port 3, DO behind DI's port 1, the
  // drive on the coupler's port 1, reached after the E-bus branch (500 ns per hop and direction).
  const DcTopology t = measure_dc_topology(master);
  EXPECT_EQ(t.parent, (std::vector<std::size_t>{0, 0, 1, 0}));
  EXPECT_EQ(t.parent_port, (std::vector<int>{0, 3, 1, 1}));
  EXPECT_EQ(t.delay, (std::vector<std::int64_t>{0, 500, 1000, 2500}));
  EXPECT_EQ(master.slaves()[3].parent_port, 1);
}

TEST(NetworkBench, OpWithDcTheDriveFollowsAndTheLoopbackReadsBack) {
  const Bench bench;
  test::VirtualLine line(bench.devices(), bench.options());
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 4u);
  master.set_mailbox_timeout(20'000'000);

  // The output terminal's byte and the input terminal's byte in the process image.
  auto offsets = [&] {
    std::uint32_t start = UINT32_MAX;
    for (const Slave& s : master.slaves()) {
      if (s.process_data.output_bytes) start = std::min(start, s.process_data.output_logical);
      if (s.process_data.input_bytes) start = std::min(start, s.process_data.input_logical);
    }
    return std::pair{master.slaves()[2].process_data.output_logical - start,
                     master.slaves()[1].process_data.input_logical - start};
  };
  std::uint64_t cycle = 0, matched = 0, compared = 0;
  std::uint8_t written = 0;
  const test::CspSineRun run = test::run_csp_sine_at_1ms(master, 1'000'000'000, [&](OpRunOptions& options) {
    options.outputs = [&, sine = options.outputs](std::span<std::uint8_t> image) {
      sine(image);
      written = static_cast<std::uint8_t>((++cycle / 50) & 1);  // channel 1 toggles every 50 cycles
      image[offsets().first] = written;
    };
    options.inputs = [&, sine = options.inputs, safeop = options.safeop_cycles](std::span<std::uint8_t> image) {
      sine(image);
      // Outputs act in Op only (after the Safe-Op cycles); then a few cycles for each change to arrive.
      if (cycle <= safeop + 50 || cycle % 50 < 5) return;
      ++compared;
      if ((image[offsets().second] & 1) == written) ++matched;
    };
  });
  ASSERT_EQ(run.drives.size(), 4u);
  test::expect_drive_followed(run, 3, [&] { return line.network().esc(1).peek_u16(0x0134); });
  EXPECT_GT(compared, 500u);
  EXPECT_EQ(matched, compared) << "the input terminal reads what the output terminal drives";
}

}  // namespace
}  // namespace vdrive::master

namespace vdrive::master {
namespace {

// An A6B of another model than the built-in product's (an ENI's MADLT15BF, 613C0005h): the master
// finds that identity in the SII and in 1018h, and the drive behaves as the A6B.
TEST(NetworkIdentity, AnA6bModelIsServedWithItsOwnProductCode) {
  network::NetworkOptions o;
  o.identities = {network::IdentityChoice{0x613C0005, 0x00020000}};
  test::VirtualLine line({"a6b"}, o);
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 1u);
  EXPECT_EQ(master.slaves()[0].info.product_code, 0x613C0005u);
  EXPECT_EQ(master.slaves()[0].info.revision, 0x00020000u);
  master.set_mailbox_timeout(20'000'000);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  EXPECT_EQ(master.sdo(0).upload_value<std::uint32_t>(0x1018, 2), 0x613C0005u);
  EXPECT_EQ(master.sdo(0).upload_value<std::uint32_t>(0x1018, 3), 0x00020000u);
}

TEST(NetworkIdentity, AProductCodeOutsideTheSeriesIsRefused) {
  network::NetworkOptions o;
  o.identities = {network::IdentityChoice{0x513C0005, 0}};
  EXPECT_THROW(test::VirtualLine({"a6b"}, o), std::invalid_argument);
}

}  // namespace
}  // namespace vdrive::master
