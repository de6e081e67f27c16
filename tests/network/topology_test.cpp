// Topology: which cablings validate() accepts, the message it gives for each impossible one
// (naming the slave and the port, 1-based as users count slaves), and the visiting order.
#include "vdrive/network/topology.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace vdrive::network {
namespace {

constexpr std::uint8_t kTwoPorts = 0x0F;   // ports 0, 1 (MII)
constexpr std::uint8_t kFourPorts = 0xFF;  // ports 0-3
constexpr std::uint8_t kThreePorts = 0x3F; // ports 0-2

Topology of(std::vector<Uplink> uplinks) { return Topology{std::move(uplinks)}; }

// The message validate() throws, or "" if it accepts.
std::string error_of(const Topology& t, std::vector<std::uint8_t> descriptors) {
  try {
    validate(t, descriptors);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Topology, TheLineAndATreeOfImplementedPortsAreAccepted) {
  EXPECT_EQ(error_of(Topology{}, {kTwoPorts, kTwoPorts, kTwoPorts}), "");
  EXPECT_EQ(error_of(Topology::line(3), {kTwoPorts, kTwoPorts, kTwoPorts}), "");
  EXPECT_EQ(error_of(Topology{}, {}), "");
  const Topology tree = of({{Uplink::kMaster, 0}, {0, 3}, {0, 1}, {0, 2}, {1, 1}});
  EXPECT_EQ(error_of(tree, {kFourPorts, kTwoPorts, kTwoPorts, kTwoPorts, kTwoPorts}), "");
  // The root need not be listed first.
  EXPECT_EQ(error_of(of({{1, 1}, {Uplink::kMaster, 0}}), {kTwoPorts, kTwoPorts}), "");
}

TEST(Topology, APortTheEscDoesNotImplementIsRefused) {
  const std::string e = error_of(of({{Uplink::kMaster, 0}, {0, 3}}), {kThreePorts, kTwoPorts});
  EXPECT_EQ(e, "topology: slave 2: cabled to port 3 of slave 1, which that ESC does not implement "
               "(port descriptor 0x3F: ports 0, 1, 2)");
  // The line needs port 1 on every slave but the last.
  EXPECT_NE(error_of(Topology{}, {0x03, kTwoPorts}).find("slave 2: in the line it hangs on port 1 of slave 1"), std::string::npos);
  EXPECT_EQ(error_of(Topology{}, {kTwoPorts, 0x03}), "") << "the last slave needs no port 1";
}

TEST(Topology, APortUsedTwiceIsRefused) {
  const std::string e = error_of(of({{Uplink::kMaster, 0}, {0, 1}, {0, 1}}), {kFourPorts, kTwoPorts, kTwoPorts});
  EXPECT_EQ(e, "topology: slave 3: cabled to port 1 of slave 1, where slave 2 already is");
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}, {Uplink::kMaster, 0}}), {kTwoPorts, kTwoPorts}),
            "topology: slave 2: cabled to the master, but slave 1 already is (the master has one port)");
}

TEST(Topology, PortZeroIsNoWayOut) {
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}, {0, 0}}), {kTwoPorts, kTwoPorts}),
            "topology: slave 2: cabled to port 0 of slave 1, which is that slave's own way in (use port 1, 2 or 3)");
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}, {0, 4}}), {kFourPorts, kTwoPorts}),
            "topology: slave 2: cabled to port 4 of slave 1: there is no such port (1, 2 or 3)");
}

TEST(Topology, AParentOutOfRangeIsRefused) {
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}, {5, 1}}), {kTwoPorts, kTwoPorts}),
            "topology: slave 2: cabled to slave 6, which does not exist (slaves 1..2, or the master)");
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}, {-3, 1}}), {kTwoPorts, kTwoPorts}),
            "topology: slave 2: cabled to slave -2, which does not exist (slaves 1..2, or the master)");
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}, {1, 1}}), {kTwoPorts, kTwoPorts}), "topology: slave 2: cabled to its own port 1");
}

TEST(Topology, ALoopIsRefusedAndNamed) {
  // Slave 1 on the master; slaves 2 and 3 hang on each other.
  const std::string e = error_of(of({{Uplink::kMaster, 0}, {2, 1}, {1, 1}}), {kTwoPorts, kTwoPorts, kTwoPorts});
  EXPECT_EQ(e, "topology: slave 2: its cables never reach the master: they form a loop "
               "(slave 2 -> port 1 of slave 3 -> port 1 of slave 2)");
  // No slave on the master at all is a loop too.
  EXPECT_NE(error_of(of({{1, 1}, {0, 1}}), {kTwoPorts, kTwoPorts}).find("never reach the master"), std::string::npos);
}

TEST(Topology, OneUplinkPerSlave) {
  EXPECT_EQ(error_of(of({{Uplink::kMaster, 0}}), {kTwoPorts, kTwoPorts}),
            "topology: 1 uplinks for 2 slaves (one per slave, or none for a line)");
  EXPECT_EQ(error_of(Topology{}, {0x0C}), "topology: slave 1: its ESC implements no port 0 (port descriptor 0x0C)");
}

TEST(Topology, TheLineIsRecognisedSpelledOutOrNot) {
  EXPECT_TRUE(is_line(Topology{}));
  EXPECT_TRUE(is_line(Topology::line(4)));
  EXPECT_TRUE(is_line(of({{Uplink::kMaster, 0}, {0, 1}})));
  EXPECT_FALSE(is_line(of({{Uplink::kMaster, 0}, {0, 2}})));
  EXPECT_FALSE(is_line(of({{1, 1}, {Uplink::kMaster, 0}})));
}

TEST(Topology, VisitingOrderIsDepthFirstInPortOrderThreeOneTwo) {
  const Topology tree = of({{Uplink::kMaster, 0}, {0, 2}, {0, 1}, {0, 3}, {3, 1}});
  EXPECT_EQ(visiting_order(tree, 5), (std::vector<std::size_t>{0, 3, 4, 2, 1}));
  EXPECT_EQ(visiting_order(Topology{}, 3), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(visiting_order(of({{1, 1}, {Uplink::kMaster, 0}}), 2), (std::vector<std::size_t>{1, 0}));
}

}  // namespace
}  // namespace vdrive::network
