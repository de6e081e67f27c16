// The ESC's four ports as a junction uses them: link, loop control and DL status per port, the
// port descriptor deciding which exist, and the receive times of every port latched by 0x0900.
#include <gtest/gtest.h>

#include "tests/esc_model/esc_test_util.hpp"

namespace vdrive::esc::test {
namespace {

EscConfig with_ports(std::uint8_t descriptor) {
  EscConfig c = default_config();
  c.port_descriptor = descriptor;
  return c;
}

struct FourPorts : EscTest {
  FourPorts() {
    esc = std::make_unique<Esc>(with_ports(0xFF), clock);
    set_station();
    PortLinks links;
    for (bool& l : links.port) l = true;
    esc->set_links(links);
  }
  std::uint16_t dl_status() { return static_cast<std::uint16_t>(fprd(0x0110, 2).data[0] | (fprd(0x0110, 2).data[1] << 8)); }
};

TEST_F(FourPorts, EveryPortWithLinkIsOpenAndForwards) {
  EXPECT_EQ(dl_status() & 0xFFF0, 0xAAF0);  // link 4-7, each loop open (8+2p = 0), communication (9+2p = 1)
  for (int p = 0; p < 4; ++p) EXPECT_TRUE(esc->port_forwards(p)) << p;
  EXPECT_EQ(fprd(0x0007, 1).data[0], 0xFF);
}

TEST_F(FourPorts, LoopControlActsPerPort) {
  fpwr(0x0101, {0xC0});  // port 3 closed, ports 0-2 auto
  EXPECT_FALSE(esc->port_forwards(3));
  EXPECT_TRUE(esc->port_forwards(1));
  EXPECT_TRUE(esc->port_forwards(2));
  EXPECT_EQ((dl_status() >> 14) & 0x03, 0x03);  // closed, link still there
  fpwr(0x0101, {0x10});  // port 2 auto close, port 3 auto again
  EXPECT_TRUE(esc->port_forwards(3));
  PortLinks links;
  links.port[0] = links.port[1] = links.port[3] = true;  // port 2 loses its link ...
  esc->set_links(links);
  links.port[2] = true;  // ... and gets it back, but stays closed until DL control is written
  esc->set_links(links);
  EXPECT_FALSE(esc->port_forwards(2));
  EXPECT_EQ(esc->peek(0x0312), 1);  // lost link counter, port 2
  fpwr(0x0101, {0x10});
  EXPECT_TRUE(esc->port_forwards(2));
}

TEST(EscPorts, APortTheDescriptorDoesNotImplementNeverForwards) {
  VirtualClock clock;
  Esc esc(with_ports(0x3F), clock);  // ports 0, 1, 2
  PortLinks links;
  for (bool& l : links.port) l = true;
  esc.set_links(links);
  EXPECT_TRUE(esc.port_forwards(2));
  EXPECT_FALSE(esc.port_forwards(3));
  const std::uint16_t s = esc.peek_u16(0x0110);
  EXPECT_EQ(s & 0x0080, 0) << "no link shown on port 3";
  EXPECT_EQ((s >> 14) & 0x03, 0x01) << "port 3 closed, no communication";
}

TEST_F(FourPorts, AWriteTo0x0900LatchesTheTimeOfEveryPort) {
  esc->set_dc_model(0.0, 5'000'000'000);
  Frame f;
  f.add(cmd::BWR, Frame::ap(0, 0x0900), {0, 0, 0, 0});
  FrameTiming timing;
  timing.port0_rx = 1'000;
  timing.port3_rx = 3'400;  // out of port 3 first, then 1, then 2
  timing.port1_rx = 4'600;
  timing.port2_rx = 5'800;
  ASSERT_TRUE(esc->process_frame(f.pdu(), timing));
  const std::vector<std::uint8_t> rx = fprd(0x0900, 16).data;
  const auto at = [&](int port) {
    const auto i = static_cast<std::size_t>(4 * port);
    return static_cast<std::uint32_t>(rx[i] | (rx[i + 1] << 8) | (rx[i + 2] << 16) | (static_cast<std::uint32_t>(rx[i + 3]) << 24));
  };
  EXPECT_EQ(at(0), static_cast<std::uint32_t>(5'000'001'000));
  EXPECT_EQ(at(1), static_cast<std::uint32_t>(5'000'004'600));
  EXPECT_EQ(at(2), static_cast<std::uint32_t>(5'000'005'800));
  EXPECT_EQ(at(3), static_cast<std::uint32_t>(5'000'003'400));
}

}  // namespace
}  // namespace vdrive::esc::test
