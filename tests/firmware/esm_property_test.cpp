// Random master traffic against the firmware on a real Esc (fixed seed, reproducible): whatever
// the wire says, the slave only ever reports a defined state, climbs at most one step per request,
// reports only codes its product defines, and leaves no serviced event pending.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::firmware {
namespace {

// Ladder position as ETG.1000.6 orders the states; Boot ranks with PreOp (one step from Init).
int ladder(std::uint8_t state) {
  switch (state) {
    case 0x1: return 0;
    case 0x2: return 1;
    case 0x3: return 1;
    case 0x4: return 2;
    case 0x8: return 3;
  }
  return -1;
}

class FirmwareEsmProperty : public ::testing::TestWithParam<std::string> {};

TEST_P(FirmwareEsmProperty, RandomTrafficKeepsTheInvariants) {
  VirtualClock clock;
  const profile::ProductProfile product = profile::load_profile(GetParam());
  esc::Esc esc(profile::make_esc_config(product), clock);
  SlaveFirmware fw(product, esc);
  fw.power_on(0);

  const std::set<std::uint16_t> codes = {
      product.al_codes.invalid_transition, product.al_codes.unknown_state,
      product.al_codes.bootstrap_not_supported, product.al_codes.invalid_mailbox_config,
      product.al_codes.invalid_boot_mailbox_config,
      // PreOp->SafeOp process-data checks (docs/process-data.md)
      product.al_codes.invalid_output_config, product.al_codes.invalid_input_config,
      product.al_codes.invalid_input_mapping, product.al_codes.invalid_output_mapping,
      product.al_codes.invalid_watchdog_config, product.al_codes.sync_watchdog};

  std::mt19937 rng(0xEC47);
  auto byte = [&] { return static_cast<std::uint8_t>(rng() & 0xFF); };
  std::vector<std::uint8_t> pdu;
  auto apwr = [&](std::uint16_t ado, std::initializer_list<std::uint8_t> data) {
    pdu.assign({static_cast<std::uint8_t>(12 + data.size()), 0x10, 0x02, 0x00, 0x00, 0x00,
                static_cast<std::uint8_t>(ado), static_cast<std::uint8_t>(ado >> 8),
                static_cast<std::uint8_t>(data.size()), 0x00, 0x00, 0x00});
    pdu.insert(pdu.end(), data);
    pdu.push_back(0);
    pdu.push_back(0);
    ASSERT_TRUE(esc.process_frame(pdu, esc::FrameTiming{}));
    if (esc.pdi_irq() != 0) fw.on_irq(0);
  };

  std::uint8_t previous = 0x1;
  int reached_op = 0;
  for (int i = 0; i < 20000; ++i) {
    const unsigned pick = rng() % 10;
    if (pick < 6) {
      // Mostly plausible requests (valid states, sometimes ack/ID), sometimes garbage.
      static constexpr std::array<std::uint8_t, 5> kStates = {1, 2, 3, 4, 8};
      std::uint8_t control = (rng() % 4 == 0) ? byte() : kStates[rng() % kStates.size()];
      if (rng() % 3 == 0) control |= 0x10;
      apwr(0x0120, {control, byte()});
    } else if (pick < 8) {
      // A good mailbox layout (so the slave gets somewhere), or a random one.
      const int n = static_cast<int>(rng() % 4);
      const auto base = static_cast<std::uint16_t>(0x0800 + 8 * n);
      apwr(static_cast<std::uint16_t>(base + 6), {0x00});
      // A good layout is enabled, so all four SMs (SafeOp checks SM2/SM3 too) are often good at once.
      const bool good = rng() % 2 == 0 && n < static_cast<int>(product.sync_managers.size());
      if (good) {
        const auto& sm = product.sync_managers[static_cast<std::size_t>(n)];
        apwr(base, {static_cast<std::uint8_t>(sm.start), static_cast<std::uint8_t>(sm.start >> 8),
                    static_cast<std::uint8_t>(sm.length),
                    static_cast<std::uint8_t>(sm.length >> 8), sm.control});
      } else {
        apwr(base, {byte(), static_cast<std::uint8_t>(0x10 + (rng() % 0x10)), byte(), 0x00,
                    byte()});
      }
      apwr(static_cast<std::uint16_t>(base + 6), {static_cast<std::uint8_t>(good ? 1 : rng() % 2)});
    } else {
      apwr(0x0806 + 8 * static_cast<std::uint16_t>(rng() % 2), {static_cast<std::uint8_t>(1)});
    }
    if (HasFatalFailure()) return;

    const auto status = static_cast<std::uint16_t>(esc.peek(0x0130) | (esc.peek(0x0131) << 8));
    const auto code = static_cast<std::uint16_t>(esc.peek(0x0134) | (esc.peek(0x0135) << 8));
    const std::uint8_t state = status & 0x0F;
    ASSERT_GE(ladder(state), 0) << "step " << i << " status 0x" << std::hex << status;
    ASSERT_LE(ladder(state) - ladder(previous), 1) << "step " << i << ": climbed more than 1 step";
    if (state == 0x3) {
      ASSERT_TRUE(product.has_bootstrap) << "step " << i;
    }
    if (status & 0x10) {
      ASSERT_TRUE(codes.count(code)) << "step " << i << " code 0x" << std::hex << code;
    } else if ((status & 0x20) == 0) {
      ASSERT_EQ(code, 0) << "step " << i << ": code without error or ID";
    }
    ASSERT_EQ(status & 0xFFC0, 0) << "step " << i << ": reserved status bits set";
    ASSERT_EQ(esc.pdi_irq(), 0u) << "step " << i << ": serviced event left pending";
    if (state == 0x8) ++reached_op;
    previous = state;
  }
  EXPECT_GT(reached_op, 0) << "the random walk never reached Op: the test would prove little";
}

INSTANTIATE_TEST_SUITE_P(Products, FirmwareEsmProperty,
                         ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::firmware
