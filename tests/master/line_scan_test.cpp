// The master against the real pieces of vdrive (profiles, SII images, ESCs, firmware, segment)
// in virtual time: scan, identities, station addresses, SII strings, Pre-Op, AL status codes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "master/master.hpp"
#include "master/registers.hpp"
#include "tests/master/virtual_line.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::master {
namespace {

class LineScan : public ::testing::Test {
protected:
  const std::vector<std::string> products{"a6b", "ds5c1", "ds1000a"};
  test::VirtualLine line{products};
  network::Network& net = line.network();
  Master master{line, line.clock()};

  std::uint16_t esc_u16(std::size_t slave, std::uint16_t address) {
    return static_cast<std::uint16_t>(net.esc(slave).peek(address) | (net.esc(slave).peek(address + 1) << 8));
  }
};

TEST_F(LineScan, FindsThreeSlavesWithTheirProfileIdentities) {
  ASSERT_EQ(master.scan(), 3u);
  ASSERT_EQ(master.slaves().size(), 3u);
  for (std::size_t i = 0; i < products.size(); ++i) {
    const auto profile = profile::load_profile(products[i]);
    const SlaveInfo& info = master.slaves()[i].info;
    SCOPED_TRACE(products[i]);
    EXPECT_EQ(info.vendor_id, profile.identity.vendor_id);
    EXPECT_EQ(info.product_code, profile.identity.product_code);
    EXPECT_EQ(info.revision, profile.identity.revision);
    EXPECT_EQ(info.serial, profile.identity.serial);
    EXPECT_EQ(info.mailbox_rx_offset, profile.mailbox.rx_offset);
    EXPECT_EQ(info.mailbox_rx_size, profile.mailbox.rx_size);
    EXPECT_EQ(info.mailbox_tx_offset, profile.mailbox.tx_offset);
    EXPECT_EQ(info.mailbox_tx_size, profile.mailbox.tx_size);
    EXPECT_EQ(info.mailbox_protocols, profile.mailbox.protocols);
  }
}

TEST_F(LineScan, AssignsStationAddressesInCableOrder) {
  ASSERT_EQ(master.scan(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(master.slaves()[i].position, i);
    EXPECT_EQ(master.slaves()[i].station, 0x1001 + i);
    EXPECT_EQ(esc_u16(i, reg::kStationAddress), 0x1001 + i) << "the ESC holds the written address";
  }
}

TEST_F(LineScan, ReadsSiiStringsAndCategories) {
  ASSERT_EQ(master.scan(), 3u);
  for (std::size_t i = 0; i < products.size(); ++i) {
    const auto profile = profile::load_profile(products[i]);
    const SlaveInfo& info = master.slaves()[i].info;
    SCOPED_TRACE(products[i]);
    EXPECT_TRUE(info.has_general);
    EXPECT_EQ(info.name, profile.identity.device_name);
    EXPECT_EQ(info.coe_details, profile.coe_details);
    ASSERT_GE(info.sync_managers.size(), 2u);
    EXPECT_EQ(info.sync_managers[0].type, 1) << "SM0 is mailbox out";
    EXPECT_EQ(info.sync_managers[1].type, 2) << "SM1 is mailbox in";
    EXPECT_EQ(info.sync_managers[0].start, profile.mailbox.rx_offset);
  }
}

TEST_F(LineScan, SlavesStartInInit) {
  ASSERT_EQ(master.scan(), 3u);
  for (const Slave& s : master.slaves()) {
    EXPECT_EQ(s.state(), AlState::Init);
    EXPECT_FALSE(s.al.error);
  }
}

TEST_F(LineScan, ReachesPreOpWithMailboxSyncManagersFromSii) {
  ASSERT_EQ(master.scan(), 3u);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  for (std::size_t i = 0; i < 3; ++i) {
    const Slave& s = master.slaves()[i];
    EXPECT_EQ(s.state(), AlState::PreOp);
    EXPECT_EQ(net.esc(i).peek(reg::kAlStatus) & 0x1F, 0x02) << "the ESC reports Pre-Op";
    // SM0/SM1 as the master wrote them: SII offsets and sizes, control 0x26/0x22, enabled.
    EXPECT_EQ(esc_u16(i, reg::kSm0), s.info.mailbox_rx_offset);
    EXPECT_EQ(esc_u16(i, reg::kSm0 + 2), s.info.mailbox_rx_size);
    EXPECT_EQ(net.esc(i).peek(reg::kSm0 + 4), 0x26);
    EXPECT_EQ(net.esc(i).peek(reg::kSm0 + 6) & 0x01, 0x01);
    EXPECT_EQ(esc_u16(i, reg::kSm0 + 8), s.info.mailbox_tx_offset);
    EXPECT_EQ(net.esc(i).peek(reg::kSm0 + 8 + 4), 0x22);
  }
}

TEST_F(LineScan, BackToInitFromPreOp) {
  ASSERT_EQ(master.scan(), 3u);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  ASSERT_TRUE(master.request_state(AlState::Init));
  for (const Slave& s : master.slaves()) EXPECT_EQ(s.state(), AlState::Init);
}

TEST_F(LineScan, BadMailboxConfigGetsTheProductsAlStatusCode) {
  ASSERT_EQ(master.scan(), 3u);
  // SM0 shorter than any product accepts.
  master.slaves()[1].mailbox_sm[0].length = 2;
  EXPECT_FALSE(master.request_state(AlState::PreOp));
  const auto profile = profile::load_profile("ds5c1");
  const Slave& bad = master.slaves()[1];
  EXPECT_TRUE(bad.al.error);
  EXPECT_EQ(bad.al.status_code, profile.al_codes.invalid_mailbox_config);
  EXPECT_EQ(bad.state(), AlState::Init);
  // The others are unaffected.
  EXPECT_EQ(master.slaves()[0].state(), AlState::PreOp);
  EXPECT_EQ(master.slaves()[2].state(), AlState::PreOp);
  // The master acknowledged the error: with a good configuration the slave comes up.
  master.slaves()[1].mailbox_sm[0].length = master.slaves()[1].info.mailbox_rx_size;
  EXPECT_TRUE(master.request_state(1, AlState::PreOp));
  EXPECT_FALSE(master.slaves()[1].al.error) << std::hex << master.slaves()[1].al.status_code;
}

TEST_F(LineScan, RescanAfterPreOpResetsToInit) {
  ASSERT_EQ(master.scan(), 3u);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  ASSERT_EQ(master.scan(), 3u);
  for (const Slave& s : master.slaves()) EXPECT_EQ(s.state(), AlState::Init);
}

TEST_F(LineScan, SeveralDatagramsInOneFrameEachGetTheirOwnAnswer) {
  ASSERT_EQ(master.scan(), 3u);
  ASSERT_TRUE(master.request_state(AlState::PreOp));
  Transport& t = master.transport();
  Frame frame;
  ASSERT_EQ(frame.add(Command::BRD, t.next_index(), station_address(0, reg::kType), 1), 0);
  for (std::uint16_t i = 0; i < 3; ++i) {
    ASSERT_GE(frame.add(Command::FPRD, t.next_index(), station_address(0x1001 + i, reg::kStationAddress), 2), 0);
  }
  ASSERT_EQ(frame.add(Command::FPRD, t.next_index(), station_address(0x1009, reg::kAlStatus), 2), 4);
  ASSERT_TRUE(t.transceive(frame));
  EXPECT_EQ(frame.wkc(0), 3) << "BRD: one per slave";
  for (std::size_t i = 1; i <= 3; ++i) {
    EXPECT_EQ(frame.wkc(i), 1);
    EXPECT_EQ(frame.data(i)[0] | (frame.data(i)[1] << 8), 0x1000 + i) << "each slave answers its own datagram";
  }
  EXPECT_EQ(frame.wkc(4), 0) << "nobody has station address 0x1009";
}

}  // namespace
}  // namespace vdrive::master
