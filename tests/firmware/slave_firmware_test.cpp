// SlaveFirmware on a real esc::Esc, driven the way a master drives a drive: auto-increment
// datagrams (APWR/APRD) that write SyncManagers and AL Control, then AL Status read back over the
// wire. Products come from the real profiles (profiles/<id>/profile.yaml); expected codes are the
// manuals' (A6B 8-2 L32952-L33933, DS5C1 L7109-L7139), written as literals.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::firmware {
namespace {

constexpr std::uint8_t kAprd = 0x01;  // ETG.1000.4 auto-increment physical read
constexpr std::uint8_t kApwr = 0x02;  // auto-increment physical write

constexpr std::uint16_t kAlControl = 0x0120;
constexpr std::uint16_t kAlStatus = 0x0130;
constexpr std::uint16_t kAlStatusCode = 0x0134;

// One slave on the bench: its ESC, its firmware, and a master's view of it.
class Bench {
public:
  explicit Bench(profile::ProductProfile p)
      : product(std::move(p)), esc(profile::make_esc_config(product), clock), fw(product, esc) {
    fw.power_on(clock.now());
  }

  // One datagram in one frame, as the first slave of a segment sees it (ADP 0).
  std::uint16_t datagram(std::uint8_t cmd, std::uint16_t ado, std::span<std::uint8_t> data) {
    std::vector<std::uint8_t> pdu;
    const std::size_t dg_len = 10 + data.size() + 2;
    pdu.push_back(static_cast<std::uint8_t>(dg_len & 0xFF));
    pdu.push_back(static_cast<std::uint8_t>(0x10 | ((dg_len >> 8) & 0x07)));  // type 1: datagrams
    pdu.push_back(cmd);
    pdu.push_back(0x00);  // index
    pdu.push_back(0x00);  // ADP 0: this slave
    pdu.push_back(0x00);
    pdu.push_back(static_cast<std::uint8_t>(ado & 0xFF));
    pdu.push_back(static_cast<std::uint8_t>(ado >> 8));
    pdu.push_back(static_cast<std::uint8_t>(data.size() & 0xFF));
    pdu.push_back(static_cast<std::uint8_t>((data.size() >> 8) & 0x07));  // last datagram
    pdu.push_back(0x00);  // IRQ
    pdu.push_back(0x00);
    pdu.insert(pdu.end(), data.begin(), data.end());
    pdu.push_back(0x00);  // working counter
    pdu.push_back(0x00);
    EXPECT_TRUE(esc.process_frame(pdu, esc::FrameTiming{clock.now()}));
    std::copy(pdu.begin() + 12, pdu.begin() + 12 + static_cast<std::ptrdiff_t>(data.size()),
              data.begin());
    const std::size_t wkc_at = 12 + data.size();
    // The event loop services the PDI interrupt after each frame.
    if (esc.pdi_irq() != 0) fw.on_irq(clock.now());
    return static_cast<std::uint16_t>(pdu[wkc_at] | (pdu[wkc_at + 1] << 8));
  }

  void write(std::uint16_t ado, std::vector<std::uint8_t> bytes) {
    EXPECT_EQ(datagram(kApwr, ado, bytes), 1) << "APWR 0x" << std::hex << ado;
  }
  void write_u16(std::uint16_t ado, std::uint16_t v) {
    write(ado, {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8)});
  }
  std::uint16_t read_u16(std::uint16_t ado) {
    std::array<std::uint8_t, 2> b{};
    EXPECT_EQ(datagram(kAprd, ado, b), 1) << "APRD 0x" << std::hex << ado;
    return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
  }

  std::uint16_t al_status() { return read_u16(kAlStatus); }
  std::uint16_t al_code() { return read_u16(kAlStatusCode); }
  void request(std::uint16_t control) { write_u16(kAlControl, control); }

  // What a master does for one SM: deactivate, write start/length/control, activate.
  void configure_sm(int n, std::uint16_t start, std::uint16_t length, std::uint8_t control,
                    bool enable) {
    const auto base = static_cast<std::uint16_t>(0x0800 + 8 * n);
    write(static_cast<std::uint16_t>(base + 6), {0x00});
    write(base, {static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
                 static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8),
                 control});
    write(static_cast<std::uint16_t>(base + 6), {static_cast<std::uint8_t>(enable ? 1 : 0)});
  }

  // The SyncManagers as the SII declares them (what SOEM and TwinCAT write): SM0/SM1, and SM2/SM3
  // sized for the default PDO mapping, which PreOp->SafeOp checks (docs/process-data.md).
  void configure_mailbox_from_sii() {
    for (int n = 0; n < static_cast<int>(product.sync_managers.size()); ++n) {
      const auto& sm = product.sync_managers.at(static_cast<std::size_t>(n));
      configure_sm(n, sm.start, sm.length, sm.control, true);
    }
  }

  VirtualClock clock;
  profile::ProductProfile product;
  esc::Esc esc;
  SlaveFirmware fw;
};

profile::ProductProfile load(const std::string& id) { return profile::load_profile(id); }

// ---- power-on and the happy path ----------------------------------------------------------

class FirmwareOnEsc : public ::testing::TestWithParam<std::string> {};

TEST_P(FirmwareOnEsc, PowerOnReportsInitWithoutError) {
  Bench b(load(GetParam()));
  EXPECT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.al_code(), 0x0000);
  EXPECT_EQ(b.esc.pdi_irq(), 0u);
}

TEST_P(FirmwareOnEsc, SiiMailboxLayoutWalksToOpAndBack) {
  Bench b(load(GetParam()));
  b.configure_mailbox_from_sii();
  b.request(0x0002);
  EXPECT_EQ(b.al_status(), 0x0002);
  b.request(0x0004);
  EXPECT_EQ(b.al_status(), 0x0004);
  b.request(0x0008);
  EXPECT_EQ(b.al_status(), 0x0008);
  EXPECT_EQ(b.al_code(), 0x0000);
  b.request(0x0001);
  EXPECT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.esc.pdi_irq(), 0u) << "every serviced event must be cleared";
}

TEST_P(FirmwareOnEsc, GoingToInitLeavesTheSyncManagersAlone) {
  Bench b(load(GetParam()));
  b.configure_mailbox_from_sii();
  b.request(0x0002);
  ASSERT_EQ(b.al_status(), 0x0002);
  b.request(0x0001);
  ASSERT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.read_u16(0x0806) & 0x01, 0x01);  // SM0 still enabled: the master reconfigures
  EXPECT_EQ(b.read_u16(0x080E) & 0x01, 0x01);
}

TEST_P(FirmwareOnEsc, InvalidAndUnknownRequestsOverTheWire) {
  Bench b(load(GetParam()));
  b.request(0x0004);  // Init -> SafeOp
  EXPECT_EQ(b.al_status(), 0x0011);
  EXPECT_EQ(b.al_code(), 0x0011);
  b.request(0x0001);  // Init clears the error, ack or not
  EXPECT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.al_code(), 0x0000);
  b.request(0x0007);  // undefined state
  EXPECT_EQ(b.al_status(), 0x0011);
  EXPECT_EQ(b.al_code(), 0x0012);
}

TEST_P(FirmwareOnEsc, UnknownRequestInOpFallsToSafeOp) {
  Bench b(load(GetParam()));
  b.configure_mailbox_from_sii();
  b.request(0x0002);
  b.request(0x0004);
  b.request(0x0008);
  ASSERT_EQ(b.al_status(), 0x0008);
  b.request(0x000F);
  EXPECT_EQ(b.al_status(), 0x0014);  // SafeOp | error (A6B L33029, DS5C1 L7114)
  EXPECT_EQ(b.al_code(), 0x0012);
}

TEST_P(FirmwareOnEsc, ErrorNeedsAckBeforeGoingUp) {
  Bench b(load(GetParam()));
  b.configure_mailbox_from_sii();
  b.request(0x0002);
  b.request(0x0008);  // PreOp -> Op: invalid
  ASSERT_EQ(b.al_status(), 0x0012);
  b.request(0x0004);  // no ack: ignored
  EXPECT_EQ(b.al_status(), 0x0012);
  EXPECT_EQ(b.al_code(), 0x0011);
  b.request(0x0014);  // SafeOp + Error Ind Ack
  EXPECT_EQ(b.al_status(), 0x0004);
  EXPECT_EQ(b.al_code(), 0x0000);
}

INSTANTIATE_TEST_SUITE_P(Products, FirmwareOnEsc, ::testing::Values("a6b", "ds5c1", "ds1000a"));

// ---- mailbox SyncManager checks: each rule violated once -> Init | error, 0x0016 -------------

struct SmViolation {
  const char* name;
  int sm;                  // which SM the master writes
  std::uint16_t start;     // 0: keep the SII value
  std::uint16_t length;    // 0: keep the SII value
  int control;             // -1: keep the SII value
  bool enable;
};

class FirmwareMailboxViolation
    : public ::testing::TestWithParam<std::tuple<std::string, SmViolation>> {};

TEST_P(FirmwareMailboxViolation, InitToPreOpFailsWith0016) {
  const auto& [id, v] = GetParam();
  Bench b(load(id));
  b.configure_mailbox_from_sii();
  const auto& sii = b.product.sync_managers.at(static_cast<std::size_t>(v.sm < 2 ? v.sm : 1));
  if (v.sm < 2) {
    b.configure_sm(v.sm, v.start ? v.start : sii.start, v.length ? v.length : sii.length,
                   v.control >= 0 ? static_cast<std::uint8_t>(v.control) : sii.control, v.enable);
  } else {
    // An enabled process-data SM placed on top of SM1.
    b.configure_sm(v.sm, sii.start, 8, 0x64, true);
  }
  b.request(0x0002);
  EXPECT_EQ(b.al_status(), 0x0011) << v.name;  // Init | error
  EXPECT_EQ(b.al_code(), 0x0016) << v.name;    // A6B Err81.1 L33440, DS5C1 E-811 L7125
}

// Violations every product's rules reject (A6B L33400-L33446, DS5C1 L7125, DS1000A SSC rules).
const SmViolation kCommonViolations[] = {
    {"SM0 disabled", 0, 0, 0, -1, false},
    {"SM1 disabled", 1, 0, 0, -1, false},
    {"SM0 shorter than 32", 0, 0, 31, -1, true},
    {"SM1 shorter than 32", 1, 0, 31, -1, true},
    {"SM0 odd start", 0, 0x1001, 0, -1, true},
    {"SM0 control = read mailbox", 0, 0, 0, 0x22, true},
    {"SM1 control = write mailbox", 1, 0, 0, 0x26, true},
    {"SM1 control = 3-buffer", 1, 0, 0, 0x20, true},
    {"SM1 on top of SM0", 1, 0x1000, 0, -1, true},
    {"SM2 on top of SM1", 2, 0, 0, -1, true},
};

INSTANTIATE_TEST_SUITE_P(
    AllProducts, FirmwareMailboxViolation,
    ::testing::Combine(::testing::Values("a6b", "ds5c1", "ds1000a"),
                       ::testing::ValuesIn(kCommonViolations)));

// An odd send-mailbox start: DS5C1 E-811 (L7125) and the SSC rules; the A6B checks the receive
// mailbox only (A6bAcceptsAnOddSendMailboxStart).
const SmViolation kOddSm1Start[] = {{"SM1 odd start", 1, 0x1201, 0, -1, true}};

INSTANTIATE_TEST_SUITE_P(OddSm1, FirmwareMailboxViolation,
                         ::testing::Combine(::testing::Values("ds5c1", "ds1000a"), ::testing::ValuesIn(kOddSm1Start)));

// DS5C1's own windows (E-811, L7125): SM0 start 1000h-10FFh, SM1 start 1200h-12FFh, SM1 >= 40,
// both <= 256, control bits 5-0.
const SmViolation kDs5c1Violations[] = {
    {"SM0 start above 10FFh", 0, 0x1400, 0x40, -1, true},
    {"SM1 start below 1200h", 1, 0x1180, 0x40, -1, true},
    {"SM1 shorter than 40", 1, 0, 39, -1, true},
    {"SM0 longer than 256", 0, 0, 258, -1, true},
    {"SM0 without AL event enable", 0, 0, 0, 0x06, true},
};

INSTANTIATE_TEST_SUITE_P(Ds5c1, FirmwareMailboxViolation,
                         ::testing::Combine(::testing::Values("ds5c1"),
                                            ::testing::ValuesIn(kDs5c1Violations)));

TEST(FirmwareOnEscMailbox, A6bAcceptsAnOddSendMailboxStart) {
  // Err81.1 names an odd address of the receive mailbox only (L33414).
  Bench b(load("a6b"));
  b.configure_sm(0, 0x1000, 0x100, 0x26, true);
  b.configure_sm(1, 0x1201, 0x100, 0x22, true);
  b.request(0x0002);
  EXPECT_EQ(b.al_status(), 0x0002);
}

TEST(FirmwareOnEscMailbox, A6bAcceptsAMailboxWithoutIrqBits) {
  // Err81.1 checks only bits 3-0 of 0804h/080Ch (L33424-L33430).
  Bench b(load("a6b"));
  b.configure_sm(0, 0x1000, 0x100, 0x06, true);
  b.configure_sm(1, 0x1200, 0x100, 0x02, true);
  b.request(0x0002);
  EXPECT_EQ(b.al_status(), 0x0002);
}

TEST(FirmwareOnEscMailbox, FixedMailboxIsAcceptedAfterAck) {
  Bench b(load("a6b"));
  b.configure_sm(0, 0x1000, 16, 0x26, true);  // too short
  b.configure_sm(1, 0x1200, 0x100, 0x22, true);
  b.request(0x0002);
  ASSERT_EQ(b.al_code(), 0x0016);
  b.configure_sm(0, 0x1000, 0x100, 0x26, true);
  b.request(0x0012);
  EXPECT_EQ(b.al_status(), 0x0002);
  EXPECT_EQ(b.al_code(), 0x0000);
}

TEST(FirmwareOnEscMailbox, DisablingSm0InPreOpDropsToInit) {
  // A6B Err81.1 is also detected in PreOP/SafeOP/OP (L33432-L33434); ESM after: Init.
  Bench b(load("a6b"));
  b.configure_mailbox_from_sii();
  b.request(0x0002);
  b.request(0x0004);
  ASSERT_EQ(b.al_status(), 0x0004);
  b.write(0x0806, {0x00});
  EXPECT_EQ(b.al_status(), 0x0011);
  EXPECT_EQ(b.al_code(), 0x0016);
  EXPECT_EQ(b.esc.pdi_irq(), 0u);
}

TEST(FirmwareOnEscMailbox, EnablingProcessDataSmsClearOfTheMailboxIsFine) {
  Bench b(load("a6b"));
  b.configure_mailbox_from_sii();
  b.request(0x0002);
  for (int n = 2; n < 4; ++n) {
    const auto& sm = b.product.sync_managers.at(static_cast<std::size_t>(n));
    b.configure_sm(n, sm.start, sm.length, sm.control, true);
  }
  EXPECT_EQ(b.al_status(), 0x0002);
  EXPECT_EQ(b.esc.pdi_irq(), 0u);
}

TEST(FirmwareOnEscMailbox, SmChangesInInitAreOnlyAcknowledged) {
  Bench b(load("ds5c1"));
  b.configure_sm(0, 0x1000, 8, 0x26, true);  // nonsense, but Init does not look
  EXPECT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.esc.pdi_irq(), 0u);
}

// ---- Bootstrap ------------------------------------------------------------------------------

TEST(FirmwareOnEscBoot, Ds5c1RefusesBootWith0013) {
  // E-802 (L7115): AL 0013h, ESM after: Init.
  Bench b(load("ds5c1"));
  b.configure_mailbox_from_sii();
  b.request(0x0003);
  EXPECT_EQ(b.al_status(), 0x0011);
  EXPECT_EQ(b.al_code(), 0x0013);
}

TEST(FirmwareOnEscBoot, A6bEntersBootWithTheBootMailboxAndLeavesToInit) {
  Bench b(load("a6b"));
  b.configure_sm(0, *b.product.mailbox.boot_rx_offset, *b.product.mailbox.boot_rx_size, 0x26, true);
  b.configure_sm(1, *b.product.mailbox.boot_tx_offset, *b.product.mailbox.boot_tx_size, 0x22, true);
  b.request(0x0003);
  EXPECT_EQ(b.al_status(), 0x0003);
  b.request(0x0002);  // Boot -> PreOp: invalid (Err80.0, L32966-L33006), stays Boot
  EXPECT_EQ(b.al_status(), 0x0013);
  EXPECT_EQ(b.al_code(), 0x0011);
  b.request(0x0001);
  EXPECT_EQ(b.al_status(), 0x0001);
}

TEST(FirmwareOnEscBoot, A6bBadBootMailboxIs0016) {
  // Err81.1 covers Init->Boot with the same code (L33432, L33440).
  Bench b(load("a6b"));
  b.configure_sm(0, 0x1000, 0x100, 0x26, true);
  b.configure_sm(1, 0x1000, 0x100, 0x22, true);  // overlaps SM0
  b.request(0x0003);
  EXPECT_EQ(b.al_status(), 0x0011);
  EXPECT_EQ(b.al_code(), 0x0016);
}

TEST(FirmwareOnEscBoot, Ds1000aBootMailboxLargerThanTheBootBufferIs0015) {
  // ETG.1000.6 0x0015 "invalid mailbox configuration (Bootstrap)"; boot mailboxes are 128 bytes.
  Bench b(load("ds1000a"));
  b.configure_sm(0, 0x1000, 0x80, 0x26, true);
  b.configure_sm(1, 0x1080, 0x100, 0x22, true);
  b.request(0x0003);
  EXPECT_EQ(b.al_status(), 0x0011);
  EXPECT_EQ(b.al_code(), 0x0015);
}

// ---- Explicit Device ID -------------------------------------------------------------------

TEST(FirmwareOnEscDeviceId, A6bReportsTheStationAliasUntilSwitchesAreSet) {
  profile::ProductProfile p = load("a6b");
  p.esc.station_alias = 0x0123;  // SII word 4 -> register 0x0012 at power-on
  Bench b(p);
  ASSERT_EQ(b.read_u16(0x0012), 0x0123);
  b.request(0x0021);
  EXPECT_EQ(b.al_status(), 0x0021);
  EXPECT_EQ(b.al_code(), 0x0123);
  b.request(0x0001);
  EXPECT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.al_code(), 0x0000);
}

TEST(FirmwareOnEscDeviceId, A6bReportsTheIdSwitches) {
  // The ID is the rotary switch + 3740h, not register 0x0012 (L5805-L5808).
  Bench b(load("a6b"));
  b.fw.set_device_id_switch(0x0207);
  b.request(0x0021);
  EXPECT_EQ(b.al_status(), 0x0021);
  EXPECT_EQ(b.al_code(), 0x0207);
}

TEST(FirmwareOnEscDeviceId, ErrorCodeWinsOverTheIdUntilAcknowledged) {
  Bench b(load("a6b"));
  b.fw.set_device_id_switch(0x0005);
  b.request(0x0024);  // Init -> SafeOp with ID request: invalid
  EXPECT_EQ(b.al_status(), 0x0031);
  EXPECT_EQ(b.al_code(), 0x0011);
  b.request(0x0031);  // Init + ack + ID
  EXPECT_EQ(b.al_status(), 0x0021);
  EXPECT_EQ(b.al_code(), 0x0005);
}

TEST(FirmwareOnEscDeviceId, Ds5c1IgnoresTheIdRequest) {
  // "Explicit Device ID 不支持" (L2335).
  Bench b(load("ds5c1"));
  b.fw.set_device_id_switch(0x0005);
  b.request(0x0021);
  EXPECT_EQ(b.al_status(), 0x0001);
  EXPECT_EQ(b.al_code(), 0x0000);
}

TEST(FirmwareOnEscDeviceId, Ds1000aReportsTheRotarySwitch) {
  // Method 3: rotary ID switch through AL Status Code (L789-L795).
  Bench b(load("ds1000a"));
  b.fw.set_device_id_switch(0x00A5);
  b.request(0x0021);
  EXPECT_EQ(b.al_status(), 0x0021);
  EXPECT_EQ(b.al_code(), 0x00A5);
}

// ---- timing -------------------------------------------------------------------------------

// In Init the only timed work is the CiA 402 drive's control step (profile.drive.control_period_ns),
// which runs whatever the EtherCAT state; ticking it leaves the AL state alone.
TEST(FirmwareOnEscTiming, OnlyTheDriveControlStepIsTimedInInit) {
  Bench b(load("a6b"));
  const Nanos period = b.product.drive.control_period_ns;
  EXPECT_LE(b.fw.next_deadline(), period);
  b.fw.tick(1'000'000);
  EXPECT_GT(b.fw.next_deadline(), 1'000'000);
  EXPECT_LE(b.fw.next_deadline(), 1'000'000 + period);
  EXPECT_EQ(b.al_status(), 0x0001);
}

}  // namespace
}  // namespace vdrive::firmware
