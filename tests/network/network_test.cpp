// Network: a line of real product slaves (profile -> ESC + firmware -> segment), driven frame by
// frame in virtual time.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::network {
namespace {

using test::ethercat_frame;
using test::first_data;
using test::first_wkc;

constexpr std::uint8_t kAprd = 0x01, kApwr = 0x02, kBrd = 0x07;

std::vector<std::uint8_t> exchange_brd(Network& net, const VirtualClock& clock) {
  auto frame = ethercat_frame(kBrd, 0, ecat::reg::kType, 1);
  return net.process_frame(frame, clock.now()) ? frame : std::vector<std::uint8_t>{};
}

class NetworkTest : public ::testing::Test {
protected:
  // Sends one frame through the line at the current virtual time; returns it as it came back
  // (empty if the line destroyed it).
  std::vector<std::uint8_t> exchange(std::vector<std::uint8_t> frame) {
    return net_.process_frame(frame, clock_.now()) ? frame : std::vector<std::uint8_t>{};
  }

  const std::vector<std::string> ids_ = {"a6b", "ds5c1", "ds1000a"};
  VirtualClock clock_{1'000'000};
  Network net_{ids_, clock_};
};

TEST_F(NetworkTest, OneSlavePerProductInCableOrder) {
  ASSERT_EQ(net_.size(), 3u);
  EXPECT_EQ(net_.segment().size(), 3u);
  for (std::size_t i = 0; i < ids_.size(); ++i) {
    EXPECT_EQ(net_.profile(i).id, ids_[i]);
    EXPECT_EQ(&net_.segment().slave(i), &net_.esc(i)) << "segment order is cable order";
    // The ESC carries its product's silicon identity.
    EXPECT_EQ(net_.esc(i).peek(ecat::reg::kType), profile::load_profile(ids_[i]).esc.type);
  }
}

TEST_F(NetworkTest, EverySlaveIsPoweredOnInInit) {
  for (std::size_t i = 0; i < net_.size(); ++i) {
    EXPECT_EQ(net_.esc(i).peek(ecat::reg::kAlStatus) & ecat::reg::kAlStateMask, ecat::reg::kAlStateInit);
  }
}

TEST_F(NetworkTest, BroadcastReadVisitsEverySlave) {
  const auto reply = exchange(ethercat_frame(kBrd, 0, ecat::reg::kType, 1));
  ASSERT_FALSE(reply.empty());
  EXPECT_EQ(first_wkc(reply), 3);
  std::uint8_t types = 0;  // BRD returns the OR of every slave's register
  for (const auto& id : ids_) types |= profile::load_profile(id).esc.type;
  EXPECT_EQ(first_data(reply)[0], types);
}

TEST_F(NetworkTest, AutoIncrementAddressesTheSlaveAtThatPosition) {
  // Position 2 (third slave) is addressed with ADP = -2.
  const auto reply = exchange(ethercat_frame(kAprd, static_cast<std::uint16_t>(-2), ecat::reg::kType, 1));
  ASSERT_FALSE(reply.empty());
  EXPECT_EQ(first_wkc(reply), 1);
  EXPECT_EQ(first_data(reply)[0], profile::load_profile("ds1000a").esc.type);
}

TEST_F(NetworkTest, FirmwareAnswersAnAlControlRequestRightAfterTheFrame) {
  // Init -> Safe-Op is not a valid transition (ETG.1000.6): the firmware, serviced on its PDI
  // IRQ after the frame, refuses it with the error flag and the product's status code.
  const std::uint16_t safe_op = 0x0004;
  auto reply = exchange(ethercat_frame(kApwr, 0, ecat::reg::kAlControl,
                                       {static_cast<std::uint8_t>(safe_op), 0}));
  ASSERT_FALSE(reply.empty());
  ASSERT_EQ(first_wkc(reply), 1);

  reply = exchange(ethercat_frame(kAprd, 0, ecat::reg::kAlStatus, 6));  // 0x0130..0x0135
  ASSERT_FALSE(reply.empty());
  const auto data = first_data(reply);
  const std::uint16_t status = static_cast<std::uint16_t>(data[0] | (data[1] << 8));
  const std::uint16_t code = static_cast<std::uint16_t>(data[4] | (data[5] << 8));
  EXPECT_EQ(status & ecat::reg::kAlStateMask, 0x0010 | ecat::reg::kAlStateInit);
  EXPECT_EQ(code, net_.profile(0).al_codes.invalid_transition);
  // The other slaves were not addressed and stay in Init without error.
  EXPECT_EQ(net_.esc(1).peek(ecat::reg::kAlStatus) & ecat::reg::kAlStateMask, ecat::reg::kAlStateInit);
}

TEST_F(NetworkTest, PowerCycleForgetsTheErrorAndTheStationAddress) {
  exchange(ethercat_frame(kApwr, 0, ecat::reg::kAlControl, {0x04, 0}));             // refused: error flag
  exchange(ethercat_frame(kApwr, 0, ecat::reg::kStationAddress, {0x01, 0x10}));    // 0x1001
  ASSERT_NE(net_.esc(0).peek(ecat::reg::kAlStatus) & 0x10, 0);
  ASSERT_EQ(net_.esc(0).peek(ecat::reg::kStationAddress), 0x01);

  net_.power_cycle(clock_.now());

  EXPECT_EQ(net_.esc(0).peek(ecat::reg::kAlStatus), ecat::reg::kAlStateInit);
  EXPECT_EQ(net_.esc(0).peek(ecat::reg::kStationAddress), 0x00);
  EXPECT_EQ(net_.esc(0).peek(ecat::reg::kAlStatusCode), 0x00);
  // The EEPROM survives: the identity still reads back through the ESC's SII interface.
  EXPECT_EQ(net_.esc(0).peek(ecat::reg::kType), net_.profile(0).esc.type);
}

TEST_F(NetworkTest, NonEtherCatFrameDoesNotComeBack) {
  EXPECT_TRUE(exchange(test::ethernet_frame(0x0800, std::vector<std::uint8_t>(46, 0))).empty());
}

TEST_F(NetworkTest, TruncatedFrameIsDestroyedNotCrashed) {
  auto frame = ethercat_frame(kBrd, 0, ecat::reg::kType, 8);
  frame.resize(frame.size() - 6);  // datagram claims more bytes than the frame holds
  EXPECT_TRUE(exchange(frame).empty());
  // The line still works afterwards.
  EXPECT_EQ(first_wkc(exchange(ethercat_frame(kBrd, 0, ecat::reg::kType, 1))), 3);
}

TEST_F(NetworkTest, TickAtTheNextDeadlineMovesItOn) {
  const Nanos first = net_.next_deadline();
  if (first == std::numeric_limits<Nanos>::max()) GTEST_SKIP() << "no timer armed after power-on";
  clock_.set(std::max(first, clock_.now()));
  net_.tick(clock_.now());
  EXPECT_GT(net_.next_deadline(), clock_.now());
}

TEST(NetworkErrors, UnknownProductIsRefused) {
  VirtualClock clock;
  const std::vector<std::string> ids = {"a6b", "nosuchdrive"};
  EXPECT_THROW(Network(ids, clock), profile::ProfileError);
}

TEST(NetworkTopology, TheOptionsCableTheSlaves) {
  // The DS5C1 on the master, the A6B behind its port 1: position 0 is the second product given.
  VirtualClock clock{1'000'000};
  NetworkOptions options;
  options.topology.uplinks = {Uplink{1, 1}, Uplink{Uplink::kMaster, 0}};
  Network net(std::vector<std::string>{"a6b", "ds5c1"}, clock, options);
  EXPECT_EQ(net.segment().uplink(0).parent, 1);
  auto frame = ethercat_frame(kAprd, 0, ecat::reg::kType, 1);
  ASSERT_TRUE(net.process_frame(frame, clock.now()));
  EXPECT_EQ(first_data(frame)[0], profile::load_profile("ds5c1").esc.type);
  EXPECT_EQ(first_wkc(exchange_brd(net, clock)), 2);
}

TEST(NetworkTopology, ATopologyTheProductsCannotMakeIsRefused) {
  VirtualClock clock;
  NetworkOptions options;
  options.topology.uplinks = {Uplink{Uplink::kMaster, 0}, Uplink{0, 2}};  // the A6B has ports 0 and 1
  try {
    Network net(std::vector<std::string>{"a6b", "ds5c1"}, clock, options);
    FAIL() << "port 2 of an A6B accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("slave 2: cabled to port 2 of slave 1"), std::string::npos) << e.what();
  }
}

TEST(NetworkErrors, AnEmptyLineReturnsNothing) {
  VirtualClock clock;
  Network net(std::vector<std::string>{}, clock);
  auto frame = ethercat_frame(kBrd, 0, ecat::reg::kType, 1);
  // No slave on the cable: a real master sees no frame come back.
  EXPECT_EQ(net.size(), 0u);
  EXPECT_EQ(net.next_deadline(), std::numeric_limits<Nanos>::max());
  EXPECT_FALSE(net.process_frame(frame, 0));
}

}  // namespace
}  // namespace vdrive::network
