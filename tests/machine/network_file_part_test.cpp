// A network file's line cut for `vdrive run --processes N` (vdrive/machine/network_file_part.hpp):
// each part keeps its slaves (numbered from its first), the wires and named signals among them and
// the faults armed on them, the master's wire faults in part 1; a tree, a wire between two parts
// and a fault by station address are refused with the file's line; `processes: N` in the file is
// read and checked the same way.
#include "vdrive/machine/network_file_part.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using namespace vdrive;

const std::string kProducts = VDRIVE_TEST_PRODUCTS_DIR;

const std::string kLine =
    "slaves:\n"
    "  - {name: a, device: a6b}\n"
    "  - {name: b, device: ds5c1}\n"
    "  - {name: c, device: ds1000a, alias: 7}\n"
    "  - {name: d, device: a6b}\n"
    "wires:\n"
    "  - {from: a.home, to: b.probe1}\n"
    "  - {from: c.home, to: d.probe1}\n"
    "signals:\n"
    "  b_home: b.home\n"
    "  d_home: d.home\n"
    "faults:\n"
    "  - {kind: drop, probability: 0.5, at: 1s}\n"
    "  - {kind: overload, slave: d, at: 2s}\n"
    "  - {kind: jam, slave: 2, at: 3s}\n";

machine::NetworkFile parse(const std::string& text) { return machine::parse_network_file(text, "n.yaml", "."); }

std::string cut_error(const std::string& text, std::size_t parts) {
  const machine::NetworkFile f = parse(text);
  try {
    machine::check_cut(f, network::split_line(f.slaves.size(), parts));
  } catch (const machine::NetworkFileError& e) {
    return e.what();
  }
  return {};
}

TEST(NetworkFilePart, EachPartKeepsItsSlavesWiresSignalsAndFaultsNumberedFromItsFirst) {
  const machine::NetworkFile f = parse(kLine);
  const std::vector<network::LinePart> parts = network::split_line(4, 2);
  machine::check_cut(f, parts);

  const machine::NetworkFile one = machine::line_part(f, parts[0]);
  ASSERT_EQ(one.slaves.size(), 2u);
  EXPECT_EQ(one.slaves[1].name, "b");
  ASSERT_EQ(one.wires.size(), 1u);
  EXPECT_EQ(one.wires[0].to.slave, 1u);
  ASSERT_EQ(one.signals.size(), 1u);
  EXPECT_EQ(one.signals[0].name, "b_home");
  ASSERT_EQ(one.faults.size(), 2u) << "the master's wire fault and the jam on slave 2";
  EXPECT_EQ(one.faults[0].spec.kind, fault::FaultKind::drop);
  EXPECT_EQ(one.faults[1].spec.slave, 2);

  const machine::NetworkFile two = machine::line_part(f, parts[1]);
  ASSERT_EQ(two.slaves.size(), 2u);
  EXPECT_EQ(two.slaves[0].name, "c");
  EXPECT_EQ(two.slaves[0].alias, 7);
  ASSERT_EQ(two.wires.size(), 1u);
  EXPECT_EQ(two.wires[0].from.slave, 0u) << "c is this part's first slave";
  EXPECT_EQ(two.wires[0].to.slave, 1u);
  ASSERT_EQ(two.signals.size(), 1u);
  EXPECT_EQ(two.signals[0].point.slave, 1u);
  ASSERT_EQ(two.faults.size(), 1u) << "only the overload on d";
  EXPECT_EQ(two.faults[0].spec.kind, fault::FaultKind::overload);
  EXPECT_EQ(two.faults[0].spec.slave, 2) << "d is this part's second slave";
  EXPECT_TRUE(two.topology.uplinks.empty()) << "a part is a line";
}

TEST(NetworkFilePart, AWireBetweenTwoPartsIsRefusedWithItsLine) {
  const std::string e = cut_error(kLine, 4);
  EXPECT_NE(e.find("n.yaml:7: wires[0] (a.home -> b.probe1): joins slave 1 (part 1, slave 1) and slave 2 "
                   "(part 2, slave 2); a wire is copied inside one process"),
            std::string::npos)
      << e;
}

TEST(NetworkFilePart, ATreeIsServedInOneProcess) {
  // tests/products/networks/bench.yaml: a coupler with a drive on port 1 and terminals on port 3.
  const machine::NetworkFile bench = machine::load_network_file(kProducts + "/networks/bench.yaml");
  EXPECT_NO_THROW(machine::check_cut(bench, network::split_line(4, 1))) << "one process serves anything";
  try {
    machine::check_cut(bench, network::split_line(4, 2));
    FAIL() << "a tree cut in two";
  } catch (const machine::NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("bench.yaml:8: slave 3 (di) is cabled to port 3 of slave 1 (coupler): the slaves form a tree; "
                                    "--processes cuts a line"),
              std::string::npos)
        << e.what();
  }
  // Parents that only say what a line is are a line.
  EXPECT_EQ(cut_error("slaves:\n  - {name: p, device: a6b}\n  - {device: ds5c1, parent: p, port: 1}\n", 2), "");
}

TEST(NetworkFilePart, AFaultByStationAddressHasNoPart) {
  const std::string e = cut_error("slaves:\n  - {device: a6b}\n  - {device: ds5c1}\n"
                                  "faults:\n  - {kind: overload, slave: 0x1002, at: 1s}\n",
                                  2);
  EXPECT_NE(e.find("n.yaml:5: a fault by station address cannot be given to one part of --processes"), std::string::npos)
      << e;
}

TEST(NetworkFilePart, ASlaveNamedByANumberIsServedInOneProcess) {
  const std::string line = "slaves:\n  - {device: a6b}\n  - {name: '7', device: ds5c1}\n  - {name: '0x10', device: ds1000a}\n";
  EXPECT_EQ(cut_error(line, 1), "") << "one process reads its name first";
  const std::string e = cut_error(line, 2);
  EXPECT_NE(e.find("n.yaml:3: slave 2 is named '7', a number: over --processes a number in a signal point is a whole-line "
                   "position"),
            std::string::npos)
      << e;
  EXPECT_NE(cut_error("slaves:\n  - {device: a6b}\n  - {name: '0x10', device: ds1000a}\n", 2).find("named '0x10'"),
            std::string::npos);
  EXPECT_EQ(cut_error("slaves:\n  - {name: x7, device: a6b}\n  - {name: 7b, device: ds5c1}\n", 2), "");
}

TEST(NetworkFilePart, TheFileSaysHowManyProcesses) {
  EXPECT_EQ(parse(kLine + "processes: 2\n").processes, 2u);
  EXPECT_EQ(parse(kLine).processes, 0u) << "not given";
  try {
    parse(kLine + "processes: 5\n");
    FAIL() << "5 parts of 4 slaves";
  } catch (const machine::NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("n.yaml:16: processes: 5 parts for 4 slave(s); give 1 to 4"), std::string::npos)
        << e.what();
  }
  try {
    parse(kLine + "processes: 4\n");
    FAIL() << "a wire between parts";
  } catch (const machine::NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("wires[0]"), std::string::npos) << e.what();
  }
}

}  // namespace
