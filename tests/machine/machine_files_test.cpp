// The test machine of issue 19 written twice: as a network file (tests/products/networks/
// machine.yaml) and as a master's ENI (machine_eni.xml, matched against tests/products/esi). Both
// must load to the same network: the same slaves with the same identities and ports, cabled into
// the same tree, visited in the same order.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/machine/eni_reader.hpp"
#include "vdrive/machine/network_file.hpp"
#include "vdrive/network/network.hpp"

namespace {

using namespace vdrive;

const std::string kProducts = VDRIVE_TEST_PRODUCTS_DIR;

network::NetworkOptions options_of(const machine::NetworkFile& f) {
  network::NetworkOptions o;
  o.topology = f.topology;
  for (const machine::NetworkSlave& s : f.slaves) o.identities.push_back(s.identity);
  return o;
}

std::vector<std::string> devices_of(const machine::NetworkFile& f) {
  std::vector<std::string> d;
  for (const machine::NetworkSlave& s : f.slaves) d.push_back(s.device);
  return d;
}

TEST(Machine, TheNetworkFileDescribesTheWholeMachine) {
  const machine::NetworkFile f = machine::load_network_file(kProducts + "/networks/machine.yaml");
  ASSERT_EQ(f.slaves.size(), 10u);
  EXPECT_EQ(f.slaves[5].device, kProducts + "/esi/junction.xml");
  EXPECT_EQ(f.slaves[6].device, "a6b");
  EXPECT_EQ(f.slaves[7].device, "a6b");
  EXPECT_EQ(f.slaves[8].device, "ds5c1");
  // The junction's two branches: port 3 (the two A6B) and port 2 (the DS5C1 and the servo).
  EXPECT_EQ(f.topology.uplinks[6].parent, 5);
  EXPECT_EQ(f.topology.uplinks[6].port, 3);
  EXPECT_EQ(f.topology.uplinks[8].parent, 5);
  EXPECT_EQ(f.topology.uplinks[8].port, 2);
  EXPECT_EQ(network::visiting_order(f.topology, 10), (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  ASSERT_EQ(f.wires.size(), 2u);
  EXPECT_EQ(f.wires[1].from.slave, 4u);  // ao 7000h:01
  EXPECT_EQ(f.wires[1].from.index, 0x7000);
  EXPECT_EQ(f.wires[1].to.slave, 3u);    // ai 6000h:11h
  EXPECT_EQ(f.wires[1].to.index, 0x6000);
  EXPECT_EQ(f.wires[1].to.subindex, 0x11);
}

TEST(Machine, TheEniLoadsToTheSameNetworkAsTheNetworkFile) {
  const machine::NetworkFile yaml = machine::load_network_file(kProducts + "/networks/machine.yaml");
  const machine::EniNetwork eni = machine::read_eni(kProducts + "/networks/machine_eni.xml", {kProducts + "/esi"});
  ASSERT_EQ(eni.network.slaves.size(), yaml.slaves.size());
  EXPECT_EQ(eni.network.slaves[3].name, "Term 4 (EL3102)");
  EXPECT_NE(eni.network.slaves[3].device.find("analog_terminals.xml:0x0C1E3052:0x00140000"), std::string::npos)
      << eni.network.slaves[3].device;
  EXPECT_NE(eni.network.slaves[5].device.find("junction.xml:0x04622C52:0x00120000"), std::string::npos)
      << eni.network.slaves[5].device;
  EXPECT_EQ(eni.network.slaves[6].device, "a6b");
  EXPECT_EQ(eni.network.slaves[8].device, "ds5c1");

  // Both as `vdrive run` builds them: the same slave at each position a frame visits, on the same
  // port of the same parent.
  const std::size_t n = yaml.slaves.size();
  VirtualClock clock;
  network::Network from_yaml(devices_of(yaml), clock, options_of(yaml));
  network::Network from_eni(devices_of(eni.network), clock, options_of(eni.network));
  const std::vector<std::size_t> yaml_order = network::visiting_order(yaml.topology, n);
  const std::vector<std::size_t> eni_order = network::visiting_order(eni.network.topology, n);
  std::vector<std::size_t> yaml_position(n), eni_position(n);
  for (std::size_t p = 0; p < n; ++p) {
    yaml_position[yaml_order[p]] = p;
    eni_position[eni_order[p]] = p;
  }
  for (std::size_t p = 0; p < n; ++p) {
    SCOPED_TRACE("position " + std::to_string(p));
    const std::size_t y = yaml_order[p], e = eni_order[p];
    const profile::Identity& a = from_yaml.profile(y).identity;
    const profile::Identity& b = from_eni.profile(e).identity;
    EXPECT_EQ(a.vendor_id, b.vendor_id);
    EXPECT_EQ(a.product_code, b.product_code);
    EXPECT_EQ(a.revision, b.revision);
    EXPECT_EQ(from_yaml.esc(y).peek_u16(0x0006), from_eni.esc(e).peek_u16(0x0006)) << "port descriptor";
    const network::Uplink uy = yaml.topology.uplinks[y], ue = eni.network.topology.uplinks[e];
    if (uy.parent == network::Uplink::kMaster || ue.parent == network::Uplink::kMaster) {
      EXPECT_EQ(uy.parent, ue.parent);
    } else {
      EXPECT_EQ(yaml_position[static_cast<std::size_t>(uy.parent)], eni_position[static_cast<std::size_t>(ue.parent)]);
      EXPECT_EQ(uy.port, ue.port);
    }
  }
  EXPECT_EQ(eni.station_addresses, (std::vector<std::uint16_t>{1001, 1002, 1003, 1004, 1005, 1006, 1007, 1008, 1009, 1010}));
}

}  // namespace
