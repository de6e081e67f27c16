// RawSocketLink and TapLink against real kernel devices: a veth pair / TAP device created by the
// test itself (needs root; skipped otherwise).
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include "tests/support/runtime_test_support.hpp"
#include "vdrive/link/raw_socket_link.hpp"
#include "vdrive/link/tap_link.hpp"

namespace vdrive::link {
namespace {

using test::ethercat_frame;
using test::ethernet_frame;

constexpr Nanos kMs = 1'000'000;

std::vector<std::uint8_t> receive_one(Link& link, Nanos timeout = 500 * kMs) {
  std::array<std::uint8_t, kMaxFrame> buf{};
  std::size_t n = link.receive(buf, timeout);
  return {buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n)};
}

// Every case runs twice: frames by recvfrom(), and from the PACKET_RX_RING (Options::rx_ring).
class RawSocketLinkTest : public ::testing::TestWithParam<bool> {
protected:
  void SetUp() override {
    if (!test::running_as_root()) GTEST_SKIP() << "needs root (veth, raw sockets)";
    veth_ = std::make_unique<test::VethPair>();
    ASSERT_TRUE(veth_->ok()) << "could not create a veth pair";
    RawSocketLink::Options options;
    options.rx_ring = GetParam();
    a_ = std::make_unique<RawSocketLink>(veth_->a(), options);
    b_ = std::make_unique<RawSocketLink>(veth_->b(), options);
  }
  std::unique_ptr<test::VethPair> veth_;
  std::unique_ptr<RawSocketLink> a_, b_;
};

TEST_P(RawSocketLinkTest, EtherCatFrameCrossesTheLinkUnchanged) {
  auto frame = ethercat_frame(0x07 /*BRD*/, 0, 0x0000, 2);
  frame.resize(60, 0);  // a padded minimum-size frame, as a NIC would send it
  frame[20] = 0xAB;
  ASSERT_TRUE(a_->send(frame));
  EXPECT_EQ(receive_one(*b_), frame);
}

TEST_P(RawSocketLinkTest, RepliesFlowTheOtherWayToo) {
  const auto frame = ethercat_frame(0x01 /*APRD*/, 0, 0x0130, 2);
  ASSERT_TRUE(b_->send(frame));
  EXPECT_EQ(receive_one(*a_), frame);
}

TEST_P(RawSocketLinkTest, ShortUnpaddedFrameIsAcceptedAtItsRealLength) {
  const auto frame = ethercat_frame(0x07, 0, 0x0000, 1);  // 14 + 2 + 10 + 1 + 2 = 29 bytes
  ASSERT_EQ(frame.size(), 29u);
  ASSERT_TRUE(a_->send(frame));
  const auto got = receive_one(*b_);
  EXPECT_EQ(got.size(), 29u);
  EXPECT_EQ(got, frame);
}

TEST_P(RawSocketLinkTest, NonEtherCatFrameIsNotDelivered) {
  const auto ipv4 = ethernet_frame(0x0800, std::vector<std::uint8_t>(46, 0x45));
  ASSERT_TRUE(a_->send(ipv4));
  EXPECT_TRUE(receive_one(*b_, 100 * kMs).empty());
  // The next EtherCAT frame is the first thing receive() returns.
  const auto ecat = ethercat_frame(0x07, 0, 0, 2);
  ASSERT_TRUE(a_->send(ecat));
  EXPECT_EQ(receive_one(*b_), ecat);
}

TEST_P(RawSocketLinkTest, AnyDestinationAndSourceMacIsAccepted) {
  auto frame = ethercat_frame(0x07, 0, 0, 2);
  // Unicast to a MAC that is not b's: only promiscuous membership lets it in.
  const std::uint8_t dst[6] = {0x02, 0x11, 0x22, 0x33, 0x44, 0x55};
  const std::uint8_t src[6] = {0x00, 0x1B, 0x21, 0xAA, 0xBB, 0xCC};
  std::copy(std::begin(dst), std::end(dst), frame.begin());
  std::copy(std::begin(src), std::end(src), frame.begin() + 6);
  ASSERT_TRUE(a_->send(frame));
  EXPECT_EQ(receive_one(*b_), frame);
}

TEST_P(RawSocketLinkTest, FramesOnOtherInterfacesAreNotReceived) {
  test::VethPair other;
  ASSERT_TRUE(other.ok());
  RawSocketLink other_a(other.a());
  ASSERT_TRUE(other_a.send(ethercat_frame(0x07, 0, 0, 2)));
  EXPECT_TRUE(receive_one(*b_, 100 * kMs).empty());
}

TEST_P(RawSocketLinkTest, VlanTaggedEtherCatArrivesWithoutItsTag) {
  // Documented limitation: the kernel removes the 802.1Q tag before a socket bound to 0x88A4
  // sees the frame and does not report it there.
  const auto plain = ethercat_frame(0x07, 0, 0, 2);
  std::vector<std::uint8_t> tagged(plain.begin(), plain.begin() + 12);
  tagged.insert(tagged.end(), {0x81, 0x00, 0x00, 0x05});  // VID 5
  tagged.insert(tagged.end(), plain.begin() + 12, plain.end());
  ASSERT_TRUE(a_->send(tagged));
  EXPECT_EQ(receive_one(*b_), plain);
}

TEST_P(RawSocketLinkTest, OwnSendsAreNotReceived) {
  ASSERT_TRUE(a_->send(ethercat_frame(0x07, 0, 0, 2)));
  EXPECT_TRUE(receive_one(*a_, 100 * kMs).empty());
}

TEST_P(RawSocketLinkTest, FrameLongerThanTheBufferIsDiscardedNotTruncated) {
  const auto big = ethercat_frame(0x07, 0, 0, 200);
  ASSERT_TRUE(a_->send(big));
  std::array<std::uint8_t, 64> small{};
  EXPECT_EQ(b_->receive(small, 200 * kMs), 0u);
  EXPECT_EQ(b_->discarded(), 1u);
}

TEST_P(RawSocketLinkTest, ReceiveWaitsForTheTimeoutWhenNothingArrives) {
  std::array<std::uint8_t, kMaxFrame> buf{};
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(b_->receive(buf, 50 * kMs), 0u);
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_GE(waited, std::chrono::milliseconds(45));
  EXPECT_LT(waited, std::chrono::seconds(2));
  EXPECT_EQ(b_->receive(buf, 0), 0u);  // a zero timeout only looks
}

// Waits up to 500 ms for frame_waiting() to say true (a veth hands a frame over in microseconds).
bool frame_arrives(Link& link) {
  for (int i = 0; i < 500; ++i) {
    if (link.frame_waiting()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

TEST_P(RawSocketLinkTest, FrameWaitingTellsWithoutTakingTheFrame) {
  EXPECT_EQ(b_->peek_cost(), GetParam() ? PeekCost::Free : PeekCost::SystemCall);
  EXPECT_FALSE(b_->frame_waiting());
  const auto frame = ethercat_frame(0x07, 0, 0x0130, 2);
  ASSERT_TRUE(a_->send(frame));
  ASSERT_TRUE(frame_arrives(*b_));
  EXPECT_TRUE(b_->frame_waiting()) << "asking twice takes nothing";
  EXPECT_EQ(receive_one(*b_, 0), frame);
  EXPECT_FALSE(b_->frame_waiting());
  EXPECT_FALSE(a_->frame_waiting()) << "our own send is not a frame waiting for us";
}

TEST_P(RawSocketLinkTest, HasAPollableDescriptor) {
  EXPECT_GE(a_->fd(), 0);
  EXPECT_EQ(a_->interface_name(), veth_->a());
  EXPECT_GT(a_->interface_index(), 0);
}

TEST_P(RawSocketLinkTest, InterfaceGoingDownAndUpKeepsTheLink) {
  ASSERT_TRUE(test::run_quiet("ip link set " + veth_->b() + " down"));
  EXPECT_TRUE(receive_one(*b_, 50 * kMs).empty());
  ASSERT_TRUE(test::run_quiet("ip link set " + veth_->b() + " up"));
  for (int i = 0; i < 200 && test::operstate(veth_->b()) != "up"; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const auto frame = ethercat_frame(0x07, 0, 0, 2);
  ASSERT_TRUE(a_->send(frame));
  EXPECT_EQ(receive_one(*b_), frame);
}

TEST_P(RawSocketLinkTest, RemovedInterfaceIsReportedNotServedForever) {
  a_.reset();
  veth_.reset();  // deletes both ends
  std::array<std::uint8_t, kMaxFrame> buf{};
  try {
    b_->receive(buf, 200 * kMs);
    FAIL() << "receive() on a removed interface returned";
  } catch (const LinkError& e) {
    EXPECT_EQ(e.kind(), LinkError::Kind::NoInterface);
    EXPECT_NE(std::string(e.what()).find("disappeared"), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(ReceivePath, RawSocketLinkTest, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "rx_ring" : "recvfrom"; });

// The ring holds 128 frames: more than that in a row, read later, all arrive in order.
TEST_P(RawSocketLinkTest, ABurstLongerThanTheRingArrivesInOrder) {
  constexpr int kFrames = 300;
  std::array<std::uint8_t, kMaxFrame> buf{};
  int received = 0;
  for (int sent = 0; sent < kFrames; ++sent) {
    auto frame = ethercat_frame(0x07, 0, 0, 4);
    frame[20] = static_cast<std::uint8_t>(sent);
    frame[21] = static_cast<std::uint8_t>(sent >> 8);
    ASSERT_TRUE(a_->send(frame));
    if (sent % 100 == 99) {  // read in bursts of 100: the ring wraps twice
      for (; received <= sent; ++received) {
        const std::size_t n = b_->receive(buf, 500 * kMs);
        ASSERT_EQ(n, frame.size()) << "frame " << received;
        EXPECT_EQ(buf[20] | (buf[21] << 8), received & 0xFFFF);
      }
    }
  }
  EXPECT_EQ(b_->receive(buf, 0), 0u);
}

TEST(RawSocketLinkErrors, MissingInterfaceIsNamed) {
  try {
    RawSocketLink link("vdtnosuch0");
    FAIL() << "opened a missing interface";
  } catch (const LinkError& e) {
    EXPECT_EQ(e.kind(), LinkError::Kind::NoInterface);
    EXPECT_STREQ(e.what(), "no interface 'vdtnosuch0'");
  }
}

TEST(RawSocketLinkErrors, OverlongNameIsRejected) {
  try {
    RawSocketLink link("a-name-far-too-long-for-linux");
    FAIL() << "accepted an interface name longer than IFNAMSIZ";
  } catch (const LinkError& e) {
    EXPECT_EQ(e.kind(), LinkError::Kind::BadName);
  }
}

TEST(RawSocketLinkErrors, InterfaceDownIsReported) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root";
  test::VethPair veth;
  ASSERT_TRUE(veth.ok());
  ASSERT_TRUE(test::run_quiet("ip link set " + veth.a() + " down"));
  try {
    RawSocketLink link(veth.a());
    FAIL() << "opened an interface that is down";
  } catch (const LinkError& e) {
    EXPECT_EQ(e.kind(), LinkError::Kind::InterfaceDown);
    EXPECT_NE(std::string(e.what()).find(veth.a()), std::string::npos);
  }
}

// Drops to an unprivileged user in a forked child and reports what opening a link does there.
void open_unprivileged_and_exit() {
  if (::setgid(65534) != 0 || ::setuid(65534) != 0) std::_Exit(10);
  try {
    RawSocketLink link("lo");
  } catch (const LinkError& e) {
    const bool names_capability = std::string(e.what()).find("CAP_NET_RAW") != std::string::npos;
    std::_Exit(e.kind() == LinkError::Kind::NotPermitted && names_capability ? 0 : 11);
  }
  std::_Exit(12);
}

TEST(RawSocketLinkErrors, WithoutPrivilegesSaysWhatIsNeeded) {
  if (!test::running_as_root()) {
    EXPECT_THROW(RawSocketLink("lo"), LinkError);
    return;
  }
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(open_unprivileged_and_exit(), ::testing::ExitedWithCode(0), "");
}

// ---- TapLink: the master side is a raw socket on the TAP interface ---------------------------

class TapLinkTest : public ::testing::Test {
protected:
  void SetUp() override {
    if (!test::running_as_root()) GTEST_SKIP() << "needs root (TAP device)";
    name_ = "vdt" + std::to_string(::getpid()) + "t";
    tap_ = std::make_unique<TapLink>(name_);
    master_ = std::make_unique<RawSocketLink>(name_);
  }
  std::string name_;
  std::unique_ptr<TapLink> tap_;
  std::unique_ptr<RawSocketLink> master_;
};

TEST_F(TapLinkTest, DeviceIsCreatedAndUp) {
  EXPECT_TRUE(test::run_quiet("ip link show " + name_ + " up"));
  EXPECT_EQ(test::operstate(name_) == "down", false);
}

TEST_F(TapLinkTest, MasterFrameArrivesAndReplyReturns) {
  const auto request = ethercat_frame(0x07, 0, 0x0000, 2);  // unpadded, 30 bytes
  ASSERT_TRUE(master_->send(request));
  EXPECT_EQ(receive_one(*tap_), request);

  auto reply = request;
  reply[reply.size() - 2] = 1;  // working counter 1
  ASSERT_TRUE(tap_->send(reply));
  EXPECT_EQ(receive_one(*master_), reply);
}

TEST_F(TapLinkTest, FrameWaitingTellsWithoutTakingTheFrame) {
  EXPECT_EQ(tap_->peek_cost(), PeekCost::SystemCall);
  const auto request = ethercat_frame(0x07, 0, 0x0000, 2);
  ASSERT_TRUE(master_->send(request));
  ASSERT_TRUE(frame_arrives(*tap_));
  EXPECT_EQ(receive_one(*tap_, 0), request);
  EXPECT_FALSE(tap_->frame_waiting());
}

TEST_F(TapLinkTest, NonEtherCatTrafficIsDiscarded) {
  ASSERT_TRUE(master_->send(ethernet_frame(0x0800, std::vector<std::uint8_t>(46, 0x45))));
  const auto ecat = ethercat_frame(0x07, 0, 0, 2);
  ASSERT_TRUE(master_->send(ecat));
  EXPECT_EQ(receive_one(*tap_), ecat);
  EXPECT_GE(tap_->discarded(), 1u);
}

TEST_F(TapLinkTest, DeletedDeviceIsReported) {
  master_.reset();
  ASSERT_TRUE(test::run_quiet("ip link del " + name_));
  std::array<std::uint8_t, kMaxFrame> buf{};
  EXPECT_THROW(tap_->receive(buf, 200 * kMs), LinkError);
}

TEST_F(TapLinkTest, ASecondLinkOnTheSameDeviceIsRefused) {
  try {
    TapLink second(name_);
    FAIL() << "two processes' worth of links on one single-queue TAP";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
  }
}

TEST(TapLinkErrors, ANameThatIsNotATapIsABadName) {
  if (!test::running_as_root()) GTEST_SKIP() << "needs root (TAP)";
  try {
    TapLink tap("lo");
    FAIL() << "attached to lo as a TAP";
  } catch (const LinkError& e) {
    EXPECT_EQ(e.kind(), LinkError::Kind::BadName);
    EXPECT_STREQ(e.what(), "'lo' exists and is not a TAP device");
  }
}

TEST_F(TapLinkTest, DeviceDisappearsWithTheLink) {
  tap_.reset();
  master_.reset();
  EXPECT_FALSE(test::run_quiet("ip link show " + name_));
}

}  // namespace
}  // namespace vdrive::link
