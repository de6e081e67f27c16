// The firmware's interrupt path allocates nothing (architecture rule: no allocation after
// start-up), counted by tests/support/allocation_counter.hpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"
#include "tests/support/allocation_counter.hpp"

namespace vdrive::firmware {
namespace {

// An APWR datagram frame (ADP 0) writing `data` at `ado`, built before counting starts.
std::vector<std::uint8_t> apwr_frame(std::uint16_t ado, std::vector<std::uint8_t> data) {
  const std::size_t len = 10 + data.size() + 2;
  std::vector<std::uint8_t> pdu = {static_cast<std::uint8_t>(len), 0x10, 0x02, 0x00, 0x00, 0x00,
                                   static_cast<std::uint8_t>(ado),
                                   static_cast<std::uint8_t>(ado >> 8),
                                   static_cast<std::uint8_t>(data.size()), 0x00, 0x00, 0x00};
  pdu.insert(pdu.end(), data.begin(), data.end());
  pdu.push_back(0);
  pdu.push_back(0);
  return pdu;
}

TEST(FirmwareNoAllocation, InterruptPathAllocatesNothing) {
  VirtualClock clock;
  const profile::ProductProfile product = profile::load_profile("a6b");
  esc::Esc esc(profile::make_esc_config(product), clock);
  SlaveFirmware fw(product, esc);
  fw.power_on(0);

  // The master's frames for a full cycle through the ESM, including refused requests, an ID
  // request, an acknowledge and an SM change that drops the slave to Init.
  std::vector<std::vector<std::uint8_t>> frames = {
      apwr_frame(0x0800, {0x00, 0x10, 0x00, 0x01, 0x26, 0x00, 0x01}),  // SM0 + enable
      apwr_frame(0x0808, {0x00, 0x12, 0x00, 0x01, 0x22, 0x00, 0x01}),  // SM1 + enable
      apwr_frame(0x0120, {0x02, 0x00}),                                // PreOp
      apwr_frame(0x0120, {0x08, 0x00}),                                // Op: invalid
      apwr_frame(0x0120, {0x14, 0x00}),                                // SafeOp + ack
      apwr_frame(0x0120, {0x28, 0x00}),                                // Op + ID request
      apwr_frame(0x0120, {0x0B, 0x00}),                                // unknown
      apwr_frame(0x0806, {0x00}),                                      // SM0 disabled
      apwr_frame(0x0120, {0x01, 0x00}),                                // Init
  };

  int serviced = 0;
  long allocations = 0;
  for (auto& frame : frames) {
    ASSERT_TRUE(esc.process_frame(frame, esc::FrameTiming{}));
    if (esc.pdi_irq() == 0) continue;
    const long before = vdrive::test::allocation_count();
    fw.on_irq(0);
    fw.tick(0);
    allocations += vdrive::test::allocation_count() - before;
    ++serviced;
  }
  EXPECT_GE(serviced, 8);  // every AL Control write and SM activation change raised the IRQ
  EXPECT_EQ(allocations, 0);
  EXPECT_EQ(esc.peek(0x0130), 0x01);  // the script ended in Init
}

}  // namespace
}  // namespace vdrive::firmware
