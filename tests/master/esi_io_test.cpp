// Simple I/O from an ESI file (tests/products/esi/io_terminals.xml: a coupler, an 8-channel digital
// input and an 8-channel digital output with EK1100/EL1008/EL2008 identities): no mailbox, process
// data in SM0, one fixed one-bit PDO per channel. The project master scans them, maps them from the
// SII and takes the line to Op; the outputs it writes arrive in the output terminal's channel
// objects, and input channel values reach the master's process image.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/machine/network_file.hpp"
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

// The analog terminals (tests/products/esi/analog_terminals.xml: EL3102/EL4102 identities, CoE
// mailbox, process data on SM2/SM3, one fixed PDO per channel: the input's are 1A00h and 1A02h)
// with a wire from output channel 1 to input channel 1. The master maps them through CoE; the
// input terminal takes Safe-Op with its two PDOs (it refused 1A02h with AL 0024h before the PDO
// limits took the ESI's PDO indexes as they are), and what the master writes to the output
// channels arrives, as raw 16-bit values, at the input channel the wire goes to.
TEST(EsiIo, AnalogOutputWiredToAnalogInputReadsBack) {
  const machine::NetworkFile file = machine::parse_network_file(
      "slaves:\n  - {name: ai, device: analog_terminals.xml:0x0c1e3052}\n"
      "  - {name: ao, device: analog_terminals.xml:0x10063052}\n"
      "wires:\n  - {from: ao 0x7000:1, to: ai 0x6000:0x11}\n",
      "analog.yaml", std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi");
  network::NetworkOptions options;
  options.wires = file.wires;
  test::VirtualLine line({file.slaves[0].device, file.slaves[1].device}, options);
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 2u);
  EXPECT_TRUE(master.slaves()[0].info.has_mailbox());
  OpRunOptions o;
  o.dc = false;
  o.cycles = 50;
  o.back_to_init = false;
  std::int16_t ch1 = 0, ch2 = 0;
  o.outputs = [](std::span<std::uint8_t> image) {  // EL4102: channel 1, channel 2
    const std::int16_t values[2] = {-12345, 777};
    std::memcpy(image.data(), values, sizeof values);
  };
  o.inputs = [&](std::span<std::uint8_t> image) {  // EL3102 after the outputs: status, value per channel
    std::memcpy(&ch1, image.data() + 4 + 2, 2);
    std::memcpy(&ch2, image.data() + 4 + 6, 2);
  };
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error << " AL status code 0x" << std::hex << line.network().esc(0).peek_u16(0x0134);
  EXPECT_EQ(r.stats.wrong_wkc, 0u);
  EXPECT_EQ(r.layout.output_bytes, 4u);
  EXPECT_EQ(r.layout.input_bytes, 8u);
  EXPECT_TRUE(master.slaves()[0].process_data.from_coe);
  ASSERT_EQ(master.slaves()[0].process_data.inputs.size(), 2u);
  EXPECT_EQ(master.slaves()[0].process_data.inputs[1].pdo, 0x1A02);
  EXPECT_EQ(ch1, -12345) << "input channel 1 reads output channel 1 through the wire";
  EXPECT_EQ(ch2, 0) << "input channel 2 is wired to nothing";
}

}  // namespace
}  // namespace vdrive::master
