// A network of slaves served from the ENI alone (tests/products/networks/eni_only.xml: a CoE module
// with its RxPDO 1601h and TxPDO 1A00h on SM2/SM3 and DC SYNC0, and a simple input terminal whose
// SM0 only the register init commands set up), as `vdrive run --eni` serves it. The project master
// scans it, sends the ENI's CoE init commands in Pre-Op as the ENI's master would, takes it to Op
// with DC and exchanges process data through the ENI's own mapping.
#include <gtest/gtest.h>

#include <string>

#include "master/master.hpp"
#include "master/op_run.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/esi/eni_slave.hpp"
#include "vdrive/machine/eni_reader.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::master {
namespace {

const std::string kEni = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/networks/eni_only.xml";

std::uint16_t value16(network::Network& net, std::size_t slave, std::uint16_t index, std::uint8_t sub) {
  od::ObjectStore& objects = net.firmware(slave).objects();
  const od::EntryDesc* e = objects.dictionary().find(index, sub);
  if (e == nullptr) return 0xDEAD;
  const auto raw = objects.raw(*e);
  return static_cast<std::uint16_t>(raw[0] | (raw.size() > 1 ? raw[1] << 8 : 0));
}

void set16(network::Network& net, std::size_t slave, std::uint16_t index, std::uint8_t sub, std::uint16_t v) {
  od::ObjectStore& objects = net.firmware(slave).objects();
  const auto raw = objects.raw(*objects.dictionary().find(index, sub));
  raw[0] = static_cast<std::uint8_t>(v);
  if (raw.size() > 1) raw[1] = static_cast<std::uint8_t>(v >> 8);
}

TEST(EniOnlyNetwork, TheMasterTakesItToOpWithTheEnisMappingAndExchangesProcessData) {
  const machine::EniNetwork eni = machine::read_eni(kEni, {});
  std::vector<std::string> devices;
  for (const machine::NetworkSlave& s : eni.network.slaves) devices.push_back(s.device);
  network::NetworkOptions options;
  options.topology = eni.network.topology;
  test::VirtualLine line(devices, options);
  network::Network& net = line.network();
  Master master{line, line.clock()};
  ASSERT_EQ(master.scan(), 2u);
  EXPECT_EQ(master.slaves()[0].info.vendor_id, 0xABCDu);
  EXPECT_EQ(master.slaves()[0].info.product_code, 0x1234u);
  EXPECT_EQ(master.slaves()[1].info.product_code, 0x5678u);
  EXPECT_FALSE(master.slaves()[1].info.has_mailbox());

  // The module's inputs and the terminal's input byte, as the devices' wiring would give them.
  set16(net, 0, 0x6000, 1, 0x1111);
  set16(net, 0, 0x6000, 2, 0x2222);
  set16(net, 0, 0x6000, 3, 0x3333);
  set16(net, 1, 0x6000, 1, 0x5A);

  OpRunOptions o;
  o.cycles = 200;
  o.back_to_init = false;
  o.mailbox_timeout = 20'000'000;
  // The ENI's CoE init commands of the Pre-Op -> Safe-Op transition, as its master sends them.
  std::size_t sent = 0;
  o.preop = [&](Master& m) {
    tinyxml2::XMLDocument doc;
    ASSERT_EQ(doc.LoadFile(kEni.c_str()), tinyxml2::XML_SUCCESS);
    const esi::XmlReading xml(kEni);
    const tinyxml2::XMLElement* slave = doc.RootElement()->FirstChildElement("Config")->FirstChildElement("Slave");
    for (const esi::EniCoeCommand& c : esi::read_eni_slave(xml, slave).coe_init_commands) {
      m.sdo(0).download(c.index, c.subindex, c.data, c.complete_access);
      ++sent;
    }
  };
  std::uint32_t outputs_at = 0, inputs_at = 0, terminal_at = 0;
  std::uint16_t in1 = 0, in3 = 0;
  std::uint8_t terminal = 0;
  o.outputs = [&](std::span<std::uint8_t> image) {
    const std::uint32_t start = master.slaves()[0].process_data.output_logical;
    outputs_at = 0;
    image[outputs_at] = 0x34;
    image[outputs_at + 1] = 0x12;
    image[outputs_at + 2] = 0x78;
    image[outputs_at + 3] = 0x56;
    inputs_at = master.slaves()[0].process_data.input_logical - start;
    terminal_at = master.slaves()[1].process_data.input_logical - start;
  };
  o.inputs = [&](std::span<std::uint8_t> image) {
    in1 = static_cast<std::uint16_t>(image[inputs_at] | image[inputs_at + 1] << 8);
    in3 = static_cast<std::uint16_t>(image[inputs_at + 4] | image[inputs_at + 5] << 8);
    terminal = image[terminal_at];
  };
  // The module has no 1C32h/1C33h (the ENI does not write them): the master notes that it could
  // not set the sync types and runs DC on the SYNC0 activation alone.
  const OpRunResult r = run_to_op(master, o);
  ASSERT_TRUE(r.reached_op) << r.error;
  EXPECT_TRUE(r.ok()) << "wrong wkc " << r.stats.wrong_wkc << ", left Op " << r.left_op;
  EXPECT_EQ(sent, 8u);
  // The ENI's mapping: 2 output words (RxPDO 1601h), 3 input words (TxPDO 1A00h) and the input byte.
  EXPECT_EQ(r.layout.output_bytes, 4u);
  EXPECT_EQ(r.layout.input_bytes, 7u);
  EXPECT_EQ(master.slaves()[0].process_data.output_bytes, 4u);
  EXPECT_EQ(master.slaves()[0].process_data.input_bytes, 6u);
  EXPECT_EQ(value16(net, 0, 0x7000, 1), 0x1234);
  EXPECT_EQ(value16(net, 0, 0x7000, 2), 0x5678);
  EXPECT_EQ(in1, 0x1111);
  EXPECT_EQ(in3, 0x3333);
  EXPECT_EQ(terminal, 0x5A);
  // What the init commands wrote is in the objects created for them.
  EXPECT_EQ(value16(net, 0, 0x8000, 1), 0x000A);
}

}  // namespace
}  // namespace vdrive::master
