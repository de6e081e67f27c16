// Networks from an ENI (tests/products/networks/bench_eni.xml: the bench as a configurator would
// describe it, plus an A6B): each slave matched to a built-in product or an ESI device of the
// search directories, the tree from PreviousPort, the equivalent network file, and the errors.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vdrive/machine/eni_reader.hpp"

namespace {

using namespace vdrive;

const std::string kEni = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/networks/bench_eni.xml";
const std::string kEsiDir = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi";

TEST(Eni, EachSlaveIsMatchedToADevice) {
  const machine::EniNetwork n = machine::read_eni(kEni, {kEsiDir});
  ASSERT_EQ(n.network.slaves.size(), 5u);
  EXPECT_EQ(n.network.slaves[0].name, "Term 1 (EK1100)");
  EXPECT_NE(n.network.slaves[0].device.find("io_terminals.xml:0x044C2C52:0x00110000"), std::string::npos);
  EXPECT_NE(n.network.slaves[3].device.find("generic_servo.xml:0x00000402:0x00010000"), std::string::npos);
  EXPECT_EQ(n.network.slaves[4].device, "a6b");
  // Another model of the A6B series: the built-in A6B with the ENI's product code and revision.
  ASSERT_TRUE(n.network.slaves[4].identity.has_value());
  EXPECT_EQ(n.network.slaves[4].identity->product_code, 0x613C0005u);
  EXPECT_EQ(n.network.slaves[4].identity->revision, 0x00020000u);
  EXPECT_EQ(n.station_addresses, (std::vector<std::uint16_t>{1001, 1002, 1003, 1004, 1005}));
  ASSERT_EQ(n.notes.size(), 5u);
  EXPECT_NE(n.notes[4].find("built-in product a6b, with the ENI's product code and revision"), std::string::npos)
      << n.notes[4];
}

TEST(Eni, PreviousPortsMakeTheTree) {
  const machine::EniNetwork n = machine::read_eni(kEni, {kEsiDir});
  const auto& up = n.network.topology.uplinks;
  ASSERT_EQ(up.size(), 5u);
  EXPECT_EQ(up[0].parent, network::Uplink::kMaster);
  EXPECT_EQ(up[1].parent, 0);
  EXPECT_EQ(up[1].port, 3);  // D
  EXPECT_EQ(up[2].parent, 1);
  EXPECT_EQ(up[2].port, 1);  // B
  EXPECT_EQ(up[3].parent, 0);
  EXPECT_EQ(up[4].parent, 3);
}

TEST(Eni, TheNetworkFileItWritesReadsBackTheSame) {
  const machine::EniNetwork n = machine::read_eni(kEni, {kEsiDir});
  const std::string yaml = machine::to_network_yaml(n.network, n.notes);
  const machine::NetworkFile f = machine::parse_network_file(yaml, "from-eni.yaml", ".");
  ASSERT_EQ(f.slaves.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(f.slaves[i].name, n.network.slaves[i].name);
    EXPECT_EQ(f.slaves[i].device, n.network.slaves[i].device);
    EXPECT_EQ(f.slaves[i].identity.has_value(), n.network.slaves[i].identity.has_value());
    EXPECT_EQ(f.topology.uplinks[i].parent, n.network.topology.uplinks[i].parent);
    EXPECT_EQ(f.topology.uplinks[i].port, n.network.topology.uplinks[i].port);
  }
}

// Without the search directory the terminals and the ESI drive have no ESI: each is served from
// what the ENI says of it (here: its identity only; the bench's ENI gives no process data), with a
// warning naming it and its identity. The A6B is still the built-in product.
TEST(Eni, WithoutItsEsiASlaveIsServedFromTheEniAlone) {
  const machine::EniNetwork n = machine::read_eni(kEni, {});
  ASSERT_EQ(n.network.slaves.size(), 5u);
  EXPECT_TRUE(n.network.slaves[0].device.ends_with("bench_eni.xml#1001")) << n.network.slaves[0].device;
  EXPECT_EQ(n.network.slaves[4].device, "a6b");
  ASSERT_EQ(n.warnings.size(), 4u);
  EXPECT_NE(n.warnings[0].find("slave 1 'Term 1 (EK1100)' (vendor 0x00000002, product 0x044C2C52, revision 0x00110000): "
                               "served from the ENI alone"), std::string::npos) << n.warnings[0];
  EXPECT_NE(n.warnings[0].find("neither a mailbox nor process data"), std::string::npos) << n.warnings[0];
}

TEST(Eni, NotAnEniIsSaidSo) {
  try {
    machine::read_eni(kEsiDir + "/generic_servo.xml", {});
    FAIL();
  } catch (const machine::NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("not an ENI file"), std::string::npos) << e.what();
  }
}

}  // namespace
