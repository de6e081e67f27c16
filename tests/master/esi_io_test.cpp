// Simple I/O from an ESI file (tests/products/esi/io_terminals.xml: a coupler, an 8-channel digital
// input and an 8-channel digital output with EK1100/EL1008/EL2008 identities): no mailbox, process
// data in SM0, one fixed one-bit PDO per channel. The project master scans them, maps them from the
// SII and takes the line to Op; the outputs it writes arrive in the output terminal's channel
// objects, and input channel values reach the master's process image.
#include <gtest/gtest.h>

#include <string>

#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::master {
namespace {

const std::string kIo = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi/io_terminals.xml";

std::uint8_t channel(network::Network& net, std::size_t slave, std::uint16_t index) {
  od::ObjectStore& objects = net.firmware(slave).objects();
  const od::EntryDesc* e = objects.dictionary().find(index, 1);
  return e ? objects.raw(*e)[0] : 0xFF;
}

TEST(EsiIo, TerminalsWithoutAMailboxScanAsTheirFileSays) {
  test::VirtualLine line({kIo + ":0x044c2c52", kIo + ":0x03f03052", kIo + ":0x07d83052"});
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  EXPECT_EQ(master.slaves()[0].info.product_code, 0x044C2C52u);
  EXPECT_EQ(master.slaves()[1].info.name, "EL1008 8Ch. Dig. Input 24V, 3ms");
  EXPECT_FALSE(master.slaves()[1].info.has_mailbox());
  EXPECT_EQ(master.slaves()[1].info.tx_pdos.size(), 8u);
  EXPECT_EQ(master.slaves()[2].info.rx_pdos.size(), 8u);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
}

TEST(EsiIo, OutputsAndInputsGoThroughProcessData) {
  test::VirtualLine line({kIo + ":0x044c2c52", kIo + ":0x03f03052", kIo + ":0x07d83052"});
  network::Network& net = line.network();
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 3u);
  // Channels 1, 3 and 8 of the input terminal are on (what its inputs' wiring would give).
  for (const std::uint16_t index : {0x6000, 0x6020, 0x6070}) {
    od::ObjectStore& objects = net.firmware(1).objects();
    objects.raw(*objects.dictionary().find(index, 1))[0] = 1;
  }
  OpRunOptions o;
  o.dc = false;
  o.cycles = 50;
  o.back_to_init = false;
  std::uint8_t seen_inputs = 0;
  o.outputs = [](std::span<std::uint8_t> image) { image[0] = 0xA5; };  // EL2008: the only output byte
  o.inputs = [&](std::span<std::uint8_t> image) { seen_inputs = image[1]; };  // EL1008 after the outputs
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_EQ(r.stats.wrong_wkc, 0u);
  EXPECT_EQ(r.layout.output_bytes, 1u);
  EXPECT_EQ(r.layout.input_bytes, 1u);
  EXPECT_EQ(seen_inputs, 0x85) << "channels 1, 3 and 8";
  for (int c = 0; c < 8; ++c)
    EXPECT_EQ(channel(net, 2, static_cast<std::uint16_t>(0x7000 + 0x10 * c)), (0xA5 >> c) & 1) << "output channel " << c + 1;
}

}  // namespace
}  // namespace vdrive::master
