// The firmware image format of docs/foe.md (byte layout, CRC-32) and the FoE server's BUSY while
// it programs an image (ETG.1000.6 5.7: BUSY carries done/entire; the master repeats the packet).
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "tests/firmware/mailbox_test_bench.hpp"
#include "vdrive/firmware/foe/firmware_image.hpp"
#include "vdrive/firmware/foe/foe_server.hpp"

namespace vdrive::firmware::foe {
namespace {

std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(FoeImage, LayoutAsDocumented) {
  const std::string payload = "123456789";
  const std::string img = make_image("DS1000A-EC", "V1.10/1.00", bytes(payload));
  ASSERT_EQ(img.size(), 48u + 9u);
  EXPECT_EQ(img.substr(0, 8), "VDFWIMG1");
  EXPECT_EQ(img.substr(8, 16), std::string("DS1000A-EC\0\0\0\0\0\0", 16));
  EXPECT_EQ(img.substr(24, 16), std::string("V1.10/1.00\0\0\0\0\0\0", 16));
  EXPECT_EQ(img.substr(40, 4), std::string("\x09\x00\x00\x00", 4));
  EXPECT_EQ(img.substr(44, 4), std::string("\x26\x39\xF4\xCB", 4)) << "CRC-32 check value 0xCBF43926";
  EXPECT_EQ(img.substr(48), payload);
}

TEST(FoeImage, ChecksNameVersionShapeLengthAndCrc) {
  std::array<char, kImageFieldSize> version{};
  std::size_t n = 0;
  const std::string ok = make_image("DS1000A-EC", "V9.87/6.54", bytes("abc"));
  EXPECT_EQ(check_image(bytes(ok), "DS1000A-EC", "V1.00/1.00", version, n), ImageCheck::Ok);
  EXPECT_EQ(std::string(version.data(), n), "V9.87/6.54");
  EXPECT_EQ(check_image(bytes(ok), "DS5C1", "V1.00/1.00", version, n), ImageCheck::WrongProduct);
  EXPECT_EQ(check_image(bytes(make_image("DS1000A-EC", "V9.87-6.54", bytes("abc"))), "DS1000A-EC", "V1.00/1.00",
                        version, n),
            ImageCheck::BadVersion);
  EXPECT_EQ(check_image(bytes(ok.substr(0, ok.size() - 1)), "DS1000A-EC", "V1.00/1.00", version, n),
            ImageCheck::Damaged);
  std::string flipped = ok;
  flipped.back() ^= 1;
  EXPECT_EQ(check_image(bytes(flipped), "DS1000A-EC", "V1.00/1.00", version, n), ImageCheck::Damaged);
  EXPECT_EQ(check_image(bytes("hello"), "DS1000A-EC", "V1.00/1.00", version, n), ImageCheck::NotAnImage);
  EXPECT_EQ(error_for(ImageCheck::Damaged), ecat::foe::ErrorCode::ChecksumError);
  EXPECT_EQ(static_cast<std::uint32_t>(error_for(ImageCheck::WrongProduct)), 0x800Du);
}

TEST(FoeImage, VersionShapeFollowsTheFactoryText) {
  EXPECT_TRUE(same_version_shape("V2.34/5.67", "V1.00/1.00"));
  EXPECT_FALSE(same_version_shape("V2.34/5.6", "V1.00/1.00"));
  EXPECT_FALSE(same_version_shape("X2.34/5.67", "V1.00/1.00"));
  EXPECT_FALSE(same_version_shape("V2.3a/5.67", "V1.00/1.00"));
}

TEST(FoeServerBusy, LastPacketIsBusyUntilProgrammedThenAcknowledged) {
  mailbox_test::Bench b(profile::load_profile("ds1000a"));
  b.configure_sm(0, 0x1000, 128, 0x26);
  b.configure_sm(1, 0x1080, 128, 0x22);
  b.request_state(ecat::AlState::Boot);
  ASSERT_EQ(b.esm.state(), ecat::AlState::Boot);
  FoeServer server(b.context, FoeOptions{b.temp.path + "/busy", kMaxFirmwareBytes, 40'000'000});
  server.set_request_window(128);
  std::array<std::uint8_t, 122> reply{};
  auto request = [&](std::vector<std::uint8_t> r, Nanos now) {
    const mailbox::Outcome o = server.on_request(r, reply, now);
    EXPECT_FALSE(o.error.has_value());
    return o.length;
  };
  const std::string name = "ECATFW__x";
  std::vector<std::uint8_t> wrq{2, 0, 0, 0, 0, 0};
  wrq.insert(wrq.end(), name.begin(), name.end());
  ASSERT_EQ(request(wrq, 0), 6u);
  ASSERT_EQ(reply[0], 4);
  const std::string img = make_image("DS1000A-EC", "V3.00/1.00", bytes("firmware"));
  std::vector<std::uint8_t> data{3, 0, 1, 0, 0, 0};
  data.insert(data.end(), img.begin(), img.end());  // 56 bytes < 116: the only and last packet
  ASSERT_EQ(request(data, 1'000'000'000), 6u);
  EXPECT_EQ(reply[0], 6) << "BUSY";
  EXPECT_EQ(reply[2] | (reply[3] << 8), 0) << "done";
  EXPECT_EQ(reply[4] | (reply[5] << 8), 100) << "entire";
  ASSERT_EQ(request(data, 1'030'000'000), 6u);  // the master repeats the packet
  EXPECT_EQ(reply[0], 6);
  EXPECT_EQ(reply[2] | (reply[3] << 8), 75);
  ASSERT_EQ(request(data, 1'040'000'000), 6u);
  EXPECT_EQ(reply[0], 4) << "programmed: ACK";
  EXPECT_EQ(reply[2], 1);
  server.restart();
  EXPECT_EQ(server.running_version(), "V3.00/1.00");
}

}  // namespace
}  // namespace vdrive::firmware::foe
