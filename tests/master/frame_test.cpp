// Frame layout against ETG.1000.4: Ethernet header, EtherCAT header, datagram headers with the
// "more follows" bit, working counters; and reply matching.
#include "master/frame.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace vdrive::master {
namespace {

TEST(Frame, EthernetAndEtherCatHeaders) {
  Frame f;
  ASSERT_EQ(f.add(Command::BRD, 0x42, 0x00000000, 2), 0);
  auto b = f.bytes();
  ASSERT_EQ(b.size(), 14u + 2u + 10u + 2u + 2u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(b[i], 0xFF) << "destination is broadcast";
  EXPECT_EQ(b[6], 0x02) << "locally administered source";
  EXPECT_EQ(b[11], 0x01);
  EXPECT_EQ(b[12], 0x88);
  EXPECT_EQ(b[13], 0xA4);
  // EtherCAT header: length 14 (one datagram with 2 data bytes), type 1.
  EXPECT_EQ(b[14], 14);
  EXPECT_EQ(b[15], 0x10);
  EXPECT_EQ(b[16], 7) << "BRD";
  EXPECT_EQ(b[17], 0x42) << "index";
  EXPECT_EQ(b[22], 2);
  EXPECT_EQ(b[23], 0) << "no more-follows bit on the last datagram";
}

TEST(Frame, SeveralDatagramsChainWithMoreFollows) {
  Frame f;
  const std::vector<std::uint8_t> payload{0xAA, 0xBB, 0xCC};
  ASSERT_EQ(f.add(Command::FPWR, 1, 0x01201001, payload), 0);
  ASSERT_EQ(f.add(Command::APRD, 2, 0x0130FFFF, 6), 1);
  auto b = f.bytes();
  ASSERT_EQ(b.size(), 16u + (10 + 3 + 2) + (10 + 6 + 2));
  EXPECT_EQ(b[14] | ((b[15] & 0x07) << 8), 15 + 18);
  // First datagram: address little-endian, length 3 with more-follows (bit 15).
  EXPECT_EQ(b[18], 0x01);
  EXPECT_EQ(b[19], 0x10);
  EXPECT_EQ(b[20], 0x20);
  EXPECT_EQ(b[21], 0x01);
  EXPECT_EQ(b[22], 3);
  EXPECT_EQ(b[23], 0x80);
  EXPECT_EQ(b[26], 0xAA);
  EXPECT_EQ(b[28], 0xCC);
  // Second datagram starts after 10 + 3 + 2 bytes.
  EXPECT_EQ(b[31], 1) << "APRD";
  EXPECT_EQ(b[32], 2);
  EXPECT_EQ(b[37], 6);
  EXPECT_EQ(b[38], 0x00);
}

TEST(Frame, RefusesWhatDoesNotFit) {
  Frame f;
  ASSERT_EQ(f.add(Command::LRD, 0, 0, 1400), 0);
  EXPECT_EQ(f.add(Command::LRD, 1, 0, 200), -1);
  Frame g;
  for (std::size_t i = 0; i < Frame::kMaxDatagrams; ++i) ASSERT_GE(g.add(Command::NOP, 0, 0, 0), 0);
  EXPECT_EQ(g.add(Command::NOP, 0, 0, 0), -1);
}

TEST(Frame, AcceptsMatchingReplyAndReadsDataAndWkc) {
  Frame f;
  ASSERT_EQ(f.add(Command::FPRD, 7, 0x01301001, 2), 0);
  std::vector<std::uint8_t> reply(f.bytes().begin(), f.bytes().end());
  reply[26] = 0x02;   // data: AL status Pre-Op
  reply[28] = 0x01;   // WKC 1
  reply[6] = 0x03;    // an ESC may set bit 1 of the source MAC; still our reply
  ASSERT_TRUE(f.accept_reply(reply));
  EXPECT_EQ(f.data(0)[0], 0x02);
  EXPECT_EQ(f.wkc(0), 1);
  EXPECT_EQ(f.bytes()[6], 0x02) << "our Ethernet header is kept";
}

TEST(Frame, RejectsOtherFramesAndGarbage) {
  Frame f;
  ASSERT_EQ(f.add(Command::FPRD, 7, 0x01301001, 2), 0);
  const std::vector<std::uint8_t> good(f.bytes().begin(), f.bytes().end());

  auto other_index = good;
  other_index[17] = 8;
  EXPECT_FALSE(f.accept_reply(other_index));
  auto other_cmd = good;
  other_cmd[16] = 5;
  EXPECT_FALSE(f.accept_reply(other_cmd));
  auto other_length = good;
  other_length[22] = 4;
  EXPECT_FALSE(f.accept_reply(other_length));
  auto truncated = good;
  truncated.resize(good.size() - 1);
  EXPECT_FALSE(f.accept_reply(truncated));
  auto wrong_type = good;
  wrong_type[15] = 0x50;
  EXPECT_FALSE(f.accept_reply(wrong_type));
  EXPECT_FALSE(f.accept_reply(std::span<const std::uint8_t>{}));
  // Nothing of the rejected frames leaked into ours.
  EXPECT_EQ(f.wkc(0), 0);
}

// Arbitrary bytes from the wire are rejected or accepted, never read past their end.
TEST(Frame, RandomRepliesAreHandledSafely) {
  std::mt19937 rng(99);
  Frame f;
  ASSERT_EQ(f.add(Command::FPRD, 3, 0x01301001, 6), 0);
  ASSERT_EQ(f.add(Command::BRD, 4, 0, 2), 1);
  const std::vector<std::uint8_t> good(f.bytes().begin(), f.bytes().end());
  int accepted = 0;
  for (int round = 0; round < 5000; ++round) {
    std::vector<std::uint8_t> reply = good;
    reply.resize(std::uniform_int_distribution<std::size_t>(0, good.size() + 8)(rng));
    const int flips = static_cast<int>(rng() % 4);
    for (int k = 0; k < flips && !reply.empty(); ++k) reply[rng() % reply.size()] = static_cast<std::uint8_t>(rng());
    accepted += f.accept_reply(reply) ? 1 : 0;
  }
  EXPECT_GT(accepted, 0) << "replies with changed data or WKC are still replies";
  EXPECT_LT(accepted, 5000);
}

}  // namespace
}  // namespace vdrive::master
