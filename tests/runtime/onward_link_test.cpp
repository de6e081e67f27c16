// The onward port's interface disappearing (a USB NIC unplugged, the next host's veth deleted) is
// the cable out for good: the line ends at the last slave here and the run goes on serving the
// master; nothing throws out of the loop's receive.
#include "vdrive/runtime/onward_link.hpp"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/link_error.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/loop_counters.hpp"

namespace vdrive::runtime {
namespace {

// A link on one end of a socket pair, so that it has an fd to poll; nothing to receive, or (the
// onward interface removed) a receive that throws as RawSocketLink's does for ENETDOWN.
class PairLink final : public link::Link {
public:
  PairLink() { EXPECT_EQ(::socketpair(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0, fds_.data()), 0); }
  ~PairLink() override {
    ::close(fds_[0]);
    ::close(fds_[1]);
  }
  std::size_t receive(std::span<std::uint8_t>, Nanos) override {
    if (removed) throw link::LinkError(link::LinkError::Kind::NoInterface, "interface 'next0' disappeared");
    return 0;
  }
  bool send(std::span<const std::uint8_t>) override { return !removed; }
  int fd() const override { return fds_[0]; }
  bool carrier() override { return !removed; }
  void make_readable() { ASSERT_EQ(::write(fds_[1], "x", 1), 1); }
  bool removed = false;

private:
  std::array<int, 2> fds_{-1, -1};
};

TEST(OnwardLinkRemoved, TheLineEndsHereAndTheRunGoesOn) {
  MonotonicClock clock;  // receive() waits in real time
  network::Network net{std::vector<std::string>{"a6b", "ds5c1"}, clock};
  net.segment().set_onward_port();
  PairLink master, onward;
  LoopCounters counters;
  OnwardLink link(master, onward, net, clock, counters);
  ASSERT_TRUE(net.segment().onward_link());

  onward.removed = true;
  onward.make_readable();  // what poll reports for a socket whose interface went away
  std::array<std::uint8_t, 1514> buf{};
  std::size_t n = 1;
  EXPECT_NO_THROW(n = link.receive(buf, 1'000'000));
  EXPECT_EQ(n, 0u);
  EXPECT_FALSE(net.segment().onward_link()) << "the cable out for good: the line closes at the last slave here";
  EXPECT_FALSE(counters.onward_link.load());
  EXPECT_NO_THROW(n = link.receive(buf, 1'000'000)) << "and stays so, without polling the dead socket";
  EXPECT_FALSE(link.frame_waiting());

  // The master still sees the slaves here: a broadcast read counts both and comes back.
  auto frame = test::ethercat_frame(0x07, 0, ecat::reg::kType, 1);
  ASSERT_TRUE(net.process_frame(frame, clock.now()));
  EXPECT_EQ(test::first_wkc(frame), 2);
}

}  // namespace
}  // namespace vdrive::runtime
