// The SII EEPROM check (profile sii_check), on the whole firmware and a real ESC, the master
// working the EEPROM through 0x0502-0x0508 as SOEM's eepromtool does:
//  - A6B Err85.3 (L33734-L33766): 0502h bits 11-14 in any ESM state, or an SII identity that is not
//    1018h's at power-on -> Init, AL status code 0051h, not clearable (L33756); the drive's alarm
//    Err85.3 (603Fh FF55h, table 8-1 L32630).
//  - DS1000A-EC: the manual is silent; the ETG slave stack code's rule: at Init->PreOp, 0502h
//    bit 11/12 -> 0051h, the slave stays in Init, acknowledgeable.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "ethercat/little_endian.hpp"
#include "tests/firmware/pdo_test_bench.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::firmware {
namespace {

constexpr std::uint16_t kInit = 0x0001, kPreOp = 0x0002, kAck = 0x0010;
constexpr std::uint16_t kInitError = 0x0011;

class SiiBench : public test::PdoBench {
public:
  explicit SiiBench(const std::string& id) : PdoBench(id) {}

  // `duration` of time: the ESC's timers and the firmware's timed steps.
  void run_for(Nanos duration) {
    const Nanos end = clock.now() + duration;
    while (clock.now() < end) {
      const Nanos step = std::min<Nanos>(fw.next_deadline() - clock.now(), 125'000);
      advance(std::max<Nanos>(step, 1));
      fw.tick(clock.now());
    }
  }
  void state(std::uint16_t control) {
    request(control);
    run_for(1'000'000);
  }
  // EEPROM commands over ECAT, as SOEM: address (and data), then the command; wait until done.
  void eeprom_read(std::uint32_t word) {
    write(0x0504, le32(word));
    write(0x0502, {0x00, 0x01});
    run_for(200'000);
  }
  void eeprom_write(std::uint32_t word, std::uint16_t value) {
    write(0x0504, le32(word));
    write(0x0508, {static_cast<std::uint8_t>(value), static_cast<std::uint8_t>(value >> 8)});
    write(0x0502, {0x01, 0x02});   // write enable + write command, one access
    run_for(200'000);
  }
  void eeprom_reload() {
    write(0x0502, {0x00, 0x04});
    run_for(200'000);
  }
  void power_cycle() {
    esc.reset();
    fw.power_on(clock.now());
    run_for(1'000'000);
  }
  std::uint16_t object_603f() {
    const od::EntryDesc* e = fw.objects().dictionary().find(0x603F, 0);
    return e ? static_cast<std::uint16_t>(ecat::get_le(std::as_const(fw.objects()).raw(*e))) : 0;
  }

private:
  static std::vector<std::uint8_t> le32(std::uint32_t v) {
    return {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v >> 16),
            static_cast<std::uint8_t>(v >> 24)};
  }
};

void expect_err85_3(SiiBench& b, const char* when) {
  SCOPED_TRACE(when);
  EXPECT_EQ(b.al_status(), kInitError) << "Init with the error flag (L33750)";
  EXPECT_EQ(b.al_code(), 0x0051) << "L33752";
  ASSERT_NE(b.fw.drive(), nullptr);
  EXPECT_EQ(b.fw.drive()->alarms().error_code(), 0xFF55) << "Err85.3";
  EXPECT_EQ(b.object_603f(), 0xFF55);
}

TEST(A6bSiiCheck, EepromThatStopsAnsweringIsErr85_3InPreOpAndCannotBeCleared) {
  SiiBench b("a6b");
  b.mailbox_layout();
  b.state(kPreOp);
  ASSERT_EQ(b.al_status(), kPreOp);
  b.eeprom_read(0x0008);
  EXPECT_EQ(b.al_status(), kPreOp) << "a good SII access changes nothing";

  b.esc.set_faults({.sii_error = true});
  b.eeprom_read(0x0008);   // the master's read ends with 0502h bit 13 (no acknowledge)
  expect_err85_3(b, "after the failed read");

  b.state(kPreOp | kAck);
  expect_err85_3(b, "acknowledge and Pre-Op: not clearable (L33756)");
  b.state(kInit | kAck);
  expect_err85_3(b, "acknowledge and Init");

  b.esc.set_faults({});
  b.power_cycle();
  EXPECT_EQ(b.al_status(), kInit) << "a power cycle with a working EEPROM clears it";
  EXPECT_EQ(b.al_code(), 0);
}

TEST(A6bSiiCheck, IdentityChangedInTheSiiIsErr85_3AtTheNextPowerOn) {
  SiiBench b("a6b");
  b.mailbox_layout();
  b.state(kPreOp);
  b.eeprom_write(0x000A, 0x1234);   // product code, low word (eepromtool -w of another identity)
  EXPECT_EQ(b.al_status(), kPreOp) << "the identity is compared when the drive reads its SII: at power-on";
  b.power_cycle();
  expect_err85_3(b, "power-on with the changed identity");
  b.mailbox_layout();
  b.state(kPreOp | kAck);
  expect_err85_3(b, "Pre-Op refused");

  // Writing the factory identity back and power cycling is the manual's remedy (L33754).
  const auto product_low = static_cast<std::uint16_t>(b.product.identity.product_code & 0xFFFF);
  b.eeprom_write(0x000A, product_low);
  b.power_cycle();
  EXPECT_EQ(b.al_status(), kInit);
  b.mailbox_layout();
  b.state(kPreOp);
  EXPECT_EQ(b.al_status(), kPreOp);
}

TEST(A6bSiiCheck, ReloadWithABadChecksumIsErr85_3) {
  SiiBench b("a6b");
  b.mailbox_layout();
  b.state(kPreOp);
  b.eeprom_write(0x0004, 0x0042);   // station alias without fixing the CRC in word 7
  EXPECT_EQ(b.al_status(), kPreOp);
  b.eeprom_reload();                // 0502h bits 11 and 12
  expect_err85_3(b, "after the reload");
}

TEST(Ds1000aSiiCheck, ChecksumErrorRefusesPreOpWith0051AndTheAcknowledgeClearsIt) {
  SiiBench b("ds1000a");
  b.eeprom_write(0x0004, 0x0042);
  b.eeprom_reload();
  EXPECT_EQ(b.al_status(), kInit) << "no check in Init itself (ETG SSC: at Init->PreOp)";
  b.mailbox_layout();
  b.state(kPreOp);
  EXPECT_EQ(b.al_status(), kInitError);
  EXPECT_EQ(b.al_code(), 0x0051);
  b.state(kInit | kAck);
  EXPECT_EQ(b.al_status(), kInit) << "acknowledgeable";
  EXPECT_EQ(b.al_code(), 0);
}

TEST(Ds1000aSiiCheck, IdentityIsNotCompared) {
  SiiBench b("ds1000a");
  b.eeprom_write(0x000A, 0x1234);
  b.power_cycle();
  b.mailbox_layout();
  b.state(kPreOp);
  EXPECT_EQ(b.al_status(), kPreOp) << "the manual names no identity check (least strict)";
}

}  // namespace
}  // namespace vdrive::firmware
