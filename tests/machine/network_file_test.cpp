// Network files: a bench described once (tests/products/networks/bench.yaml: a coupler with two
// terminals on its E-bus port and an ESI drive on its second port, a loopback wire), read into the
// slaves, topology, aliases and wires the network is built from; mistakes named by file and line.
#include <gtest/gtest.h>

#include <string>

#include "vdrive/machine/network_file.hpp"

namespace {

using namespace vdrive;

const std::string kProducts = VDRIVE_TEST_PRODUCTS_DIR;

std::string error_of(const std::string& text) {
  try {
    machine::parse_network_file(text, "n.yaml", kProducts + "/networks");
  } catch (const machine::NetworkFileError& e) {
    return e.what();
  }
  return {};
}

TEST(NetworkFile, ReadsTheBench) {
  const machine::NetworkFile f = machine::load_network_file(kProducts + "/networks/bench.yaml");
  ASSERT_EQ(f.slaves.size(), 4u);
  EXPECT_EQ(f.slaves[1].name, "servo");
  EXPECT_EQ(f.slaves[1].device, kProducts + "/esi/generic_servo.xml");
  EXPECT_EQ(f.slaves[1].alias, 0x0102);
  ASSERT_EQ(f.topology.uplinks.size(), 4u);
  EXPECT_EQ(f.topology.uplinks[0].parent, network::Uplink::kMaster);
  EXPECT_EQ(f.topology.uplinks[1].parent, 0);
  EXPECT_EQ(f.topology.uplinks[1].port, 1);
  EXPECT_EQ(f.topology.uplinks[2].port, 3);
  EXPECT_EQ(f.topology.uplinks[3].parent, 2);
  // The frame visits the coupler, its E-bus terminals (port 3), then the drive on port 1.
  EXPECT_EQ(network::visiting_order(f.topology, 4), (std::vector<std::size_t>{0, 2, 3, 1}));
  ASSERT_EQ(f.wires.size(), 1u);
  EXPECT_EQ(f.wires[0].from.slave, 3u);
  EXPECT_EQ(f.wires[0].from.index, 0x7000);
  EXPECT_EQ(f.wires[0].to.slave, 2u);
  EXPECT_EQ(f.wires[0].to.subindex, 1);
}

TEST(NetworkFile, WithoutParentsTheSlavesFormALine) {
  const machine::NetworkFile f = machine::parse_network_file("slaves:\n  - {device: a6b}\n  - {device: ds5c1}\n", "n.yaml", ".");
  EXPECT_TRUE(f.topology.uplinks.empty());
  EXPECT_EQ(f.slaves[1].name, "slave 2");
}

TEST(NetworkFile, AnUnknownKeyGetsASuggestion) {
  const std::string e = error_of("slaves:\n  - {device: a6b, parnet: 1}\n");
  EXPECT_NE(e.find("n.yaml:2: slaves[0]: unknown key 'parnet', did you mean 'parent'?"), std::string::npos) << e;
}

// Found by fuzz_config: an empty document was refused without a line.
TEST(NetworkFile, AnEmptyFileIsRefusedAtLine1) {
  for (const char* text : {"", "# nothing but a comment\n"}) {
    const std::string e = error_of(text);
    EXPECT_EQ(e.rfind("n.yaml:1: no content: expected a mapping with 'slaves'", 0), 0u) << e;
  }
}

TEST(NetworkFile, AnUnknownDeviceListsTheProducts) {
  const std::string e = error_of("slaves:\n  - {device: a7b}\n");
  EXPECT_NE(e.find("n.yaml:2: slaves[0].device:"), std::string::npos) << e;
  EXPECT_NE(e.find("a6b"), std::string::npos) << e;
}

TEST(NetworkFile, ABrokenEsiFileIsNamed) {
  const std::string e = error_of("slaves:\n  - {device: ../esi/none.xml}\n");
  EXPECT_NE(e.find("none.xml: cannot read the ESI file"), std::string::npos) << e;
}

TEST(NetworkFile, AnImpossiblePortIsNamed) {
  // The A6B has two ports (0 and 1): nothing can be cabled to its port 3.
  const std::string e = error_of("slaves:\n  - {device: a6b}\n  - {device: ds5c1, parent: 1, port: 3}\n");
  EXPECT_NE(e.find("n.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("port 3"), std::string::npos) << e;
}

TEST(NetworkFile, AWireNamesASlaveAndAnEntryOrAConnection) {
  EXPECT_EQ(error_of("slaves:\n  - {name: a, device: a6b}\nwires:\n  - {from: a 0x6041:0, to: b 0x6040:0}\n"),
            "n.yaml:4: wires[0].to: 'b 0x6040:0': no slave 'b' (names: a; or a position 1-1)");
  EXPECT_EQ(error_of("slaves:\n  - {name: a, device: a6b}\nwires:\n  - {from: a 6041, to: a 0x6040:0}\n"),
            "n.yaml:4: wires[0].from: 'a 6041': the entry is INDEX:SUBINDEX, e.g. 0x7000:1");
  EXPECT_EQ(error_of("slaves:\n  - {name: a, device: a6b}\nwires:\n  - {from: a.hom, to: a 0x6040:0}\n"),
            "n.yaml:4: wires[0].from: 'a.hom': no plant connection 'hom' (connections: negative_limit, "
            "positive_limit, home, probe1, probe2, brake_release)");
  EXPECT_EQ(error_of("slaves:\n  - {name: a, device: a6b}\nwires:\n  - {from: a.home, to: a.home}\n"),
            "n.yaml:4: wires[0]: 'from' and 'to' are the same point");
}

TEST(NetworkFile, PlantConnectionsAndNamedSignals) {
  const machine::NetworkFile f = machine::parse_network_file(
      "slaves:\n  - {name: x, device: a6b}\n  - {name: y, device: ds5c1}\nwires:\n"
      "  - {from: x.positive_limit, to: y.probe1}\nsignals:\n  limit: x.positive_limit\n  y_mode: y 0x6060:0\n",
      "n.yaml", ".");
  ASSERT_EQ(f.wires.size(), 1u);
  EXPECT_EQ(f.wires[0].from.plant, network::PlantConnection::positive_limit);
  EXPECT_EQ(f.wires[0].to.slave, 1u);
  EXPECT_EQ(f.wires[0].to.plant, network::PlantConnection::probe1);
  ASSERT_EQ(f.signals.size(), 2u);
  EXPECT_EQ(f.signals[0].name, "limit");
  EXPECT_EQ(f.signals[0].origin, "n.yaml:7");
  EXPECT_EQ(f.signals[1].point, (network::SignalPoint{1, std::nullopt, 0x6060, 0}));
  const network::NetworkOptions o = machine::network_options(f);
  EXPECT_EQ(o.slave_names, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(o.signals.size(), 2u);
  EXPECT_EQ(o.wires.size(), 1u);
}

TEST(NetworkFile, FaultsAreArmedWithTheCataloguesFieldsAndATime) {
  const machine::NetworkFile f = machine::parse_network_file(
      "slaves:\n  - {name: x, device: a6b}\n  - {name: y, device: ds5c1}\nfaults:\n"
      "  - {kind: link_down, slave: x, port: 1, at: 5s, duration: 200ms}\n  - {kind: jam, slave: 2}\n",
      "n.yaml", ".");
  ASSERT_EQ(f.faults.size(), 2u);
  EXPECT_EQ(f.faults[0].spec.kind, fault::FaultKind::link_down);
  EXPECT_EQ(f.faults[0].spec.slave, 1);
  EXPECT_EQ(f.faults[0].spec.port, 1);
  EXPECT_EQ(f.faults[0].spec.duration, 200'000'000);
  EXPECT_EQ(f.faults[0].at, 5'000'000'000);
  EXPECT_EQ(f.faults[0].origin, "n.yaml:5");
  EXPECT_EQ(f.faults[1].spec.kind, fault::FaultKind::jam);
  EXPECT_EQ(f.faults[1].spec.slave, 2);
  EXPECT_EQ(f.faults[1].at, 0);
}

TEST(NetworkFile, AFaultMistakeIsNamedWithItsLineAndField) {
  const std::string head = "slaves:\n  - {name: x, device: a6b}\nfaults:\n";
  EXPECT_NE(error_of(head + "  - {kind: wobble}\n").find("n.yaml:4: faults[0].kind: unknown fault kind"), std::string::npos)
      << error_of(head + "  - {kind: wobble}\n");
  EXPECT_EQ(error_of(head + "  - {kind: jam, slave: z}\n"), "n.yaml:4: faults[0].slave: no slave 'z' (a name or a position 1-1)");
  EXPECT_EQ(error_of(head + "  - {kind: jam, slave: x, probability: 0.5}\n"),
            "n.yaml:4: faults[0].probability: does not apply to kind jam");
  EXPECT_EQ(error_of(head + "  - {kind: jam, slave: x, at: 5}\n"),
            "n.yaml:4: faults[0].at: expected a time with a unit (e.g. 5s, 250ms)");
  EXPECT_EQ(error_of(head + "  - {kind: drop, duration: soon}\n"),
            "n.yaml:4: faults[0].duration: 'soon' is not a time with a unit (e.g. 250ms, 1.5s)");
}

TEST(NetworkFile, SignalNamesAreChecked) {
  EXPECT_EQ(error_of("slaves:\n  - {name: x, device: a6b}\nsignals:\n  9lives: x.home\n"),
            "n.yaml:4: signals: '9lives' is not a signal name (letters, digits, '_' and '-', not starting with a digit)");
  EXPECT_EQ(error_of("slaves:\n  - {name: x, device: a6b}\nsignals:\n  door: x 0x6000\n"),
            "n.yaml:4: signals.door: 'x 0x6000': the entry is INDEX:SUBINDEX, e.g. 0x7000:1");
  EXPECT_EQ(error_of("slaves:\n  - {name: x, device: a6b}\nsignals: [x.home]\n"),
            "n.yaml:3: signals: expected a mapping NAME: POINT (SLAVE INDEX:SUB or SLAVE.CONNECTION)");
}

TEST(NetworkFile, NamesAreUnique) {
  const std::string e = error_of("slaves:\n  - {name: x, device: a6b}\n  - {name: x, device: a6b}\n");
  EXPECT_NE(e.find("n.yaml:3: slaves[1].name: 'x' is used twice"), std::string::npos) << e;
}

TEST(NetworkFile, NotYamlIsSaidSo) {
  const std::string e = error_of("slaves: [\n");
  EXPECT_NE(e.find("n.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("not YAML"), std::string::npos) << e;
}

}  // namespace


namespace {

TEST(NetworkFileIdentity, ABuiltInProductTakesAnIdentityOfItsSeries) {
  const vdrive::machine::NetworkFile f = vdrive::machine::parse_network_file(
      "slaves:\n  - {device: a6b, product_code: 0x613C0005, revision: 0x20000}\n", "n.yaml", ".");
  ASSERT_TRUE(f.slaves[0].identity.has_value());
  EXPECT_EQ(f.slaves[0].identity->product_code, 0x613C0005u);
  EXPECT_EQ(f.slaves[0].identity->revision, 0x20000u);
}

TEST(NetworkFileIdentity, AnIdentityOutsideTheSeriesIsRefused) {
  const std::string e = error_of("slaves:\n  - {device: a6b, product_code: 0x513C0005}\n");
  EXPECT_NE(e.find("n.yaml:2: slaves[0].product_code: a6b covers 0x60380005 under mask 0xF0000000, not 0x513C0005"),
            std::string::npos)
      << e;
  const std::string d = error_of("slaves:\n  - {device: ds5c1, product_code: 0x10305071}\n");
  EXPECT_NE(d.find("under mask 0xFFFFFFFF"), std::string::npos) << d;
}

}  // namespace
