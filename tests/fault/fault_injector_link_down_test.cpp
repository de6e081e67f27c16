// link_down on a line of real products: the cable named by the slave it leads into, or by either
// end with `port`; the frame turns where the cable is cut and the working counter says so.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::fault {
namespace {

constexpr std::uint8_t kBrd = 0x07;

class LinkDown : public ::testing::Test {
protected:
  // Working counter of a broadcast read, or -1 if nothing came back.
  int brd_wkc() {
    auto frame = test::ethercat_frame(kBrd, 0, ecat::reg::kType, 1);
    clock_.advance(1'000'000);
    if (!net_.process_frame(frame, clock_.now())) return -1;
    return test::first_wkc(frame);
  }
  FaultSpec link_down(int slave, int port = 0) {
    FaultSpec s;
    s.kind = FaultKind::link_down;
    s.slave = slave;
    s.port = port;
    return s;
  }

  VirtualClock clock_{1'000'000};
  network::Network net_{std::vector<std::string>{"a6b", "ds5c1", "ds1000a"}, clock_};
  FaultInjector injector_{net_, nullptr};
};

TEST_F(LinkDown, TheCableIntoASlave) {
  const int id = injector_.inject(link_down(2), clock_.now());
  EXPECT_EQ(brd_wkc(), 1);
  EXPECT_EQ(describe(link_down(2)), "link_down cable into slave 2");
  injector_.clear(id, clock_.now());
  EXPECT_EQ(brd_wkc(), 3);
}

TEST_F(LinkDown, TheSameCableNamedAtThePortItLeaves) {
  const int id = injector_.inject(link_down(1, 1), clock_.now());
  EXPECT_EQ(describe(link_down(1, 1)), "link_down cable at slave 1 port 1");
  EXPECT_FALSE(net_.segment().port_cable_connected(1, 0)) << "the cable into slave 2";
  EXPECT_EQ(brd_wkc(), 1);
  // Named from both ends at once: it heals only when neither fault is left.
  const int other = injector_.inject(link_down(2), clock_.now());
  injector_.clear(id, clock_.now());
  EXPECT_EQ(brd_wkc(), 1);
  injector_.clear(other, clock_.now());
  EXPECT_EQ(brd_wkc(), 3);
}

TEST_F(LinkDown, PortZeroIsTheCableIntoTheSlave) {
  injector_.inject(link_down(1, 0), clock_.now());
  EXPECT_EQ(brd_wkc(), -1) << "the master's own cable: nothing comes back";
  injector_.clear_all(clock_.now());
  EXPECT_EQ(brd_wkc(), 3);
}

TEST_F(LinkDown, APortWithNothingCabledIsRefused) {
  try {
    injector_.inject(link_down(3, 1), clock_.now());
    FAIL() << "no cable at the last slave's port 1";
  } catch (const FaultError& e) {
    EXPECT_NE(std::string(e.what()).find("nothing is cabled to port 1 of slave 3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(injector_.inject(link_down(1, 2), clock_.now()), FaultError) << "a6b has no port 2";
  EXPECT_EQ(brd_wkc(), 3);
}

}  // namespace
}  // namespace vdrive::fault
