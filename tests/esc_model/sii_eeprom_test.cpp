// SiiEeprom: the ET1100 EEPROM interface as a master (ECAT) and a microcontroller (PDI) use it.
#include "esc_model/sii_eeprom.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

namespace vdrive::esc {
namespace {

// Independent bit-serial CRC-8 (x^8+x^2+x+1, init 0xFF, MSB first): one message bit per step,
// not the byte-wise form the implementation uses.
std::uint8_t reference_crc8(const std::uint8_t* data, std::size_t n) {
  std::uint8_t crc = 0xFF;
  for (std::size_t i = 0; i < n; ++i) {
    for (int bit = 7; bit >= 0; --bit) {
      const bool feedback = ((crc >> 7) & 1) != ((data[i] >> bit) & 1);
      crc = static_cast<std::uint8_t>(crc << 1);
      if (feedback) crc ^= 0x07;
    }
  }
  return crc;
}

// 256-byte image: an EL-style configuration area (PDI control 0x0C80 ... alias 0x1234) with a
// correct CRC, then words counting up so that every read can be checked against its address.
std::vector<std::uint8_t> make_image(bool good_crc = true) {
  std::vector<std::uint8_t> img(256);
  const std::uint16_t config[7] = {0x0C80, 0x6E00, 0x0000, 0x0000, 0x1234, 0x0000, 0x0000};
  for (int w = 0; w < 7; ++w) {
    img[2 * w] = static_cast<std::uint8_t>(config[w]);
    img[2 * w + 1] = static_cast<std::uint8_t>(config[w] >> 8);
  }
  img[14] = reference_crc8(img.data(), 14) ^ (good_crc ? 0 : 0x5A);
  img[15] = 0;
  for (std::size_t w = 8; w < img.size() / 2; ++w) {
    img[2 * w] = static_cast<std::uint8_t>(w);
    img[2 * w + 1] = static_cast<std::uint8_t>(0xA0 + (w & 0x0F));
  }
  return img;
}

std::uint16_t expected_word(std::size_t w) { return static_cast<std::uint16_t>((w & 0xFF) | ((0xA0 + (w & 0x0F)) << 8)); }

constexpr std::uint16_t kBusy = 0x8000;
constexpr std::uint16_t kAckError = 0x2000;
constexpr std::uint16_t kWriteEnableError = 0x4000;
constexpr std::uint16_t kChecksumError = 0x0800;
constexpr std::uint16_t kDeviceInfoError = 0x1000;
constexpr Nanos kReadDone = SiiEeprom::kCommandOverhead + SiiEeprom::kReadWords * SiiEeprom::kReadTimePerWord;
constexpr Nanos kWriteDone = SiiEeprom::kCommandOverhead + SiiEeprom::kWriteTime;

struct Master {
  SiiEeprom& e;
  bool ecat = true;

  std::uint16_t status(Nanos now) {
    std::array<std::uint8_t, 2> b{};
    e.read(0x2, b, now, ecat);
    return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
  }
  // As SOEM does: command word + 32-bit address in one 6-byte write to 0x0502.
  void command(std::uint16_t control, std::uint32_t address, Nanos now) {
    const std::array<std::uint8_t, 6> b{static_cast<std::uint8_t>(control), static_cast<std::uint8_t>(control >> 8),
                                        static_cast<std::uint8_t>(address), static_cast<std::uint8_t>(address >> 8),
                                        static_cast<std::uint8_t>(address >> 16), static_cast<std::uint8_t>(address >> 24)};
    e.write(0x2, b, now, ecat);
  }
  std::uint16_t data_word(int i, Nanos now) {
    std::array<std::uint8_t, 2> b{};
    e.read(static_cast<std::uint16_t>(0x8 + 2 * i), b, now, ecat);
    return static_cast<std::uint16_t>(b[0] | (b[1] << 8));
  }
};

TEST(SiiCrc, MatchesBitSerialReferenceAndKnownVectors) {
  const auto img = make_image();
  EXPECT_EQ(sii_config_crc(std::span(img).first(14)), reference_crc8(img.data(), 14));
  // Check value of this CRC-8 (poly 0x07, init 0xFF, unreflected) over "123456789".
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(sii_config_crc(check), 0xFB);
  const std::uint8_t zeros[14] = {};
  EXPECT_EQ(sii_config_crc(zeros), reference_crc8(zeros, 14));
}

TEST(SiiEeprom, ResetValuesAdvertiseEightByteReadsAndGoodChecksum) {
  SiiEeprom e(make_image());
  Master m{e};
  const std::uint16_t st = m.status(0);
  EXPECT_EQ(st & 0x0040, 0x0040);  // 8-byte reads
  EXPECT_EQ(st & 0x0080, 0);       // 256 bytes: one address byte
  EXPECT_EQ(st & 0x0020, 0);       // no emulation
  EXPECT_EQ(st & (kChecksumError | kDeviceInfoError | kBusy), 0);
  EXPECT_TRUE(e.config_area_valid());
  EXPECT_TRUE(e.take_reload_done());
  EXPECT_FALSE(e.take_reload_done());
}

TEST(SiiEeprom, LargeImageSelectsTwoAddressBytes) {
  SiiEeprom e(std::vector<std::uint8_t>(4096, 0xFF));
  Master m{e};
  EXPECT_EQ(m.status(0) & 0x0080, 0x0080);
}

TEST(SiiEeprom, BadChecksumSetsChecksumAndDeviceInfoErrors) {
  SiiEeprom e(make_image(false));
  Master m{e};
  EXPECT_EQ(m.status(0) & (kChecksumError | kDeviceInfoError), kChecksumError | kDeviceInfoError);
  EXPECT_FALSE(e.config_area_valid());
  EXPECT_FALSE(e.take_reload_done());
}

TEST(SiiEeprom, ReadFillsEightBytesAfterBusyTime) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0100, 0x40, 1000);
  EXPECT_EQ(m.status(1000) & (kBusy | 0x0700), kBusy | 0x0100);
  EXPECT_EQ(m.status(1000 + kReadDone - 1) & kBusy, kBusy);
  EXPECT_EQ(e.next_deadline(), 1000 + kReadDone);
  EXPECT_EQ(m.status(1000 + kReadDone) & (kBusy | 0x0700 | kAckError), 0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(m.data_word(i, 1000 + kReadDone), expected_word(0x40 + i));
  // A master that reads only 4 bytes gets the first two words.
  std::array<std::uint8_t, 4> four{};
  e.read(0x8, four, 1000 + kReadDone, true);
  EXPECT_EQ(four[0] | (four[1] << 8), expected_word(0x40));
  EXPECT_EQ(four[2] | (four[3] << 8), expected_word(0x41));
}

TEST(SiiEeprom, DataIsUpdatedOnlyWhenTheCommandCompletes) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0100, 0x10, 0);
  EXPECT_EQ(m.data_word(0, kReadDone - 1), 0);  // still busy: old contents
  e.tick(kReadDone);
  EXPECT_EQ(e.next_deadline(), INT64_MAX);
  EXPECT_EQ(m.data_word(0, kReadDone), expected_word(0x10));
}

TEST(SiiEeprom, ReadBeyondImageReturnsFfff) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0100, 126, 0);  // words 126,127 exist; 128,129 do not
  EXPECT_EQ(m.data_word(0, kReadDone), expected_word(126));
  EXPECT_EQ(m.data_word(1, kReadDone), expected_word(127));
  EXPECT_EQ(m.data_word(2, kReadDone), 0xFFFF);
  EXPECT_EQ(m.data_word(3, kReadDone), 0xFFFF);
}

TEST(SiiEeprom, WriteNeedsWriteEnableInTheSameAccess) {
  SiiEeprom e(make_image());
  Master m{e};
  const std::array<std::uint8_t, 2> data{0xCD, 0xAB};
  e.write(0x8, data, 0, true);
  m.command(0x0001, 0, 0);           // write enable alone ...
  m.command(0x0200, 0x20, 10);       // ... then a write command without it
  EXPECT_EQ(m.status(10) & (kWriteEnableError | kBusy), kWriteEnableError);
  EXPECT_EQ(e.word(0x20), expected_word(0x20));

  EXPECT_EQ(m.status(10) & 0x0001, 0);  // write enable does not stick
  m.command(0x0201, 0x20, 20);       // write + enable together
  EXPECT_EQ(m.status(20) & (kWriteEnableError | kBusy | 0x0001), kBusy | 0x0001);  // old errors cleared
  EXPECT_EQ(e.word(0x20), expected_word(0x20));
  EXPECT_EQ(m.status(20 + kWriteDone) & kBusy, 0);
  EXPECT_EQ(e.word(0x20), 0xABCD);
  EXPECT_EQ(e.image()[0x40], 0xCD);
}

TEST(SiiEeprom, NoCommandClearsErrorBits) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0200, 0x20, 0);
  ASSERT_EQ(m.status(0) & kWriteEnableError, kWriteEnableError);
  m.command(0x0000, 0, 1);
  EXPECT_EQ(m.status(1) & (kWriteEnableError | kAckError), 0);
}

TEST(SiiEeprom, InvalidCommandIsAnAckError) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0300, 0, 0);
  EXPECT_EQ(m.status(0) & (kAckError | kBusy), kAckError);
}

TEST(SiiEeprom, CommandWhileBusyIsIgnoredAndFlagged) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0100, 0x10, 0);
  m.command(0x0100, 0x50, 5);  // ignored, address not taken either
  EXPECT_EQ(m.status(5) & (kAckError | kBusy), kAckError | kBusy);
  EXPECT_EQ(m.data_word(0, kReadDone), expected_word(0x10));
  EXPECT_EQ(e.next_deadline(), INT64_MAX);
}

TEST(SiiEeprom, InjectedReadErrorSetsAckError) {
  SiiEeprom e(make_image());
  Master m{e};
  e.set_no_acknowledge(true);
  m.command(0x0100, 0x10, 0);
  EXPECT_EQ(m.status(kReadDone) & (kAckError | kBusy), kAckError);
  e.set_no_acknowledge(false);
  m.command(0x0100, 0x10, kReadDone);
  EXPECT_EQ(m.status(2 * kReadDone) & (kAckError | kBusy), 0);
  EXPECT_EQ(m.data_word(0, 2 * kReadDone), expected_word(0x10));
}

TEST(SiiEeprom, ReloadRechecksTheConfigurationArea) {
  constexpr Nanos kReloadDone = SiiEeprom::kCommandOverhead + SiiEeprom::kConfigWords * SiiEeprom::kReadTimePerWord;
  SiiEeprom e(make_image());
  Master m{e};
  ASSERT_TRUE(e.take_reload_done());
  // Corrupt word 0 through the interface, then reload: checksum error.
  const std::array<std::uint8_t, 2> zero{0x00, 0x00};
  e.write(0x8, zero, 0, true);
  m.command(0x0201, 0, 0);
  Nanos t = kWriteDone;
  m.command(0x0400, 0, t);
  EXPECT_EQ(m.status(t) & (kBusy | 0x0700), kBusy | 0x0400);
  EXPECT_FALSE(e.take_reload_done());  // not before the reload has finished
  t += kReloadDone;
  EXPECT_EQ(m.status(t) & (kBusy | kChecksumError | kDeviceInfoError), kChecksumError | kDeviceInfoError);
  EXPECT_FALSE(e.take_reload_done());

  // Restore the word and reload again: loaded.
  const std::array<std::uint8_t, 2> orig{0x80, 0x0C};
  e.write(0x8, orig, t, true);
  m.command(0x0201, 0, t);
  t += kWriteDone;
  m.command(0x0400, 0, t);
  t += kReloadDone;
  e.tick(t);
  EXPECT_EQ(m.status(t) & (kBusy | kChecksumError | kDeviceInfoError), 0);
  EXPECT_TRUE(e.take_reload_done());
}

TEST(SiiEeprom, PdiOwnershipBlocksEcatWrites) {
  SiiEeprom e(make_image());
  Master ecat{e, true};
  Master pdi{e, false};
  // PDI cannot take the interface unless ECAT offers it.
  const std::array<std::uint8_t, 1> take{0x01};
  e.write(0x1, take, 0, false);
  ecat.command(0x0100, 0x10, 0);
  EXPECT_EQ(ecat.status(0) & kBusy, kBusy);
  e.tick(kReadDone);

  const std::array<std::uint8_t, 1> offer{0x01};
  e.write(0x0, offer, kReadDone, true);
  e.write(0x1, take, kReadDone, false);
  std::array<std::uint8_t, 1> state{};
  e.read(0x1, state, kReadDone, true);
  EXPECT_EQ(state[0], 0x01);

  ecat.command(0x0100, 0x20, kReadDone);  // ignored: PDI owns it
  EXPECT_EQ(ecat.status(kReadDone) & kBusy, 0);
  pdi.command(0x0100, 0x30, kReadDone);   // the PDI may read
  EXPECT_EQ(pdi.data_word(0, 2 * kReadDone), expected_word(0x30));
  // The PDI needs no ECAT write enable.
  const std::array<std::uint8_t, 2> data{0x11, 0x22};
  e.write(0x8, data, 2 * kReadDone, false);
  pdi.command(0x0200, 0x30, 2 * kReadDone);
  e.tick(2 * kReadDone + kWriteDone);
  EXPECT_EQ(e.word(0x30), 0x2211);

  // Force ECAT access: the PDI loses the interface.
  const std::array<std::uint8_t, 1> force{0x03};
  const Nanos t = 2 * kReadDone + kWriteDone;
  e.write(0x0, force, t, true);
  e.read(0x1, state, t, true);
  EXPECT_EQ(state[0], 0x00);
  ecat.command(0x0100, 0x40, t);
  EXPECT_EQ(ecat.status(t) & kBusy, kBusy);
}

TEST(SiiEeprom, WriteBeyondImageIsAnAckError) {
  SiiEeprom e(make_image());
  Master m{e};
  m.command(0x0201, 200, 0);  // image has 128 words
  EXPECT_EQ(m.status(kWriteDone) & (kAckError | kBusy), kAckError);
  EXPECT_EQ(e.size_bytes(), 256u);
}

TEST(SiiEeprom, RandomRegisterTrafficKeepsInvariants) {
  SiiEeprom e(make_image());
  std::mt19937 rng(777);
  std::array<std::uint8_t, 16> buf{};
  Nanos now = 0;
  for (int i = 0; i < 20'000; ++i) {
    now += static_cast<Nanos>(rng() % 20'000);
    const auto offset = static_cast<std::uint16_t>(rng() % 16);
    const std::size_t len = 1 + rng() % (16 - offset);
    for (auto& b : buf) b = static_cast<std::uint8_t>(rng());
    if (rng() % 2) {
      e.write(offset, std::span(buf).first(len), now, rng() % 4 != 0);
    } else {
      e.read(offset, std::span(buf).first(len), now, true);
    }
    Master m{e};
    const std::uint16_t st = m.status(now);
    ASSERT_EQ(st & 0x0040, 0x0040);
    ASSERT_EQ((st & kBusy) != 0, e.next_deadline() != INT64_MAX);
    ASSERT_EQ(e.size_bytes(), 256u);
  }
}

}  // namespace
}  // namespace vdrive::esc
