// Cutting a process image into LRW pieces (master/lrw_split.hpp) and the frames of one cycle built
// from them (master/cycle_frames.hpp): contiguous pieces that cover the image, cuts on the slaves'
// FMMU windows, each piece's expected working counter, frame 0 carrying FRMW/BRD/BWR.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "master/al_state.hpp"
#include "master/cycle_frames.hpp"
#include "master/lrw_split.hpp"

namespace vdrive::master {
namespace {

// `n` slaves laid out as configure_process_data lays them: every output window, then every input.
std::vector<SlaveImage> line_of(std::size_t n, std::uint32_t out, std::uint32_t in, std::uint32_t start = 0) {
  std::vector<SlaveImage> slaves;
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<std::uint32_t>(i);
    slaves.push_back({start + k * out, out, start + static_cast<std::uint32_t>(n) * out + k * in, in});
  }
  return slaves;
}

bool inside(std::uint32_t at, std::uint32_t length, const LrwPiece& p) {
  return at >= p.logical && at + length <= p.logical + p.bytes;
}

TEST(LrwSplit, AnImageThatFitsIsOnePieceWithTheWholeCounter) {
  const auto slaves = line_of(3, 25, 31, 0x100);
  const auto pieces = split_process_image(0x100, 3 * 56, slaves, CycleFrames::kMaxLrwBytes);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].logical, 0x100u);
  EXPECT_EQ(pieces[0].offset, 0u);
  EXPECT_EQ(pieces[0].bytes, 3 * 56);
  EXPECT_EQ(pieces[0].expected_wkc, 9) << "3 per slave: +2 outputs written, +1 inputs read";
}

TEST(LrwSplit, PiecesCoverTheImageAndNeverCutAWindow) {
  const std::size_t n = 200;
  const std::uint32_t out = 25, in = 43;
  const auto slaves = line_of(n, out, in);
  const std::uint32_t size = static_cast<std::uint32_t>(n) * (out + in);
  const auto pieces = split_process_image(0, size, slaves, CycleFrames::kMaxLrwBytes);
  ASSERT_GE(pieces.size(), (size + CycleFrames::kMaxLrwBytes - 1) / CycleFrames::kMaxLrwBytes);
  std::uint32_t at = 0;
  for (const LrwPiece& p : pieces) {
    EXPECT_EQ(p.offset, at) << "contiguous, in order";
    EXPECT_EQ(p.logical, at);
    EXPECT_GT(p.bytes, 0);
    EXPECT_LE(p.bytes, CycleFrames::kMaxLrwBytes);
    at += p.bytes;
  }
  EXPECT_EQ(at, size) << "the whole image";
  for (std::size_t s = 0; s < n; ++s) {
    int holding_outputs = 0, holding_inputs = 0;
    for (const LrwPiece& p : pieces) {
      holding_outputs += inside(slaves[s].output_logical, out, p);
      holding_inputs += inside(slaves[s].input_logical, in, p);
    }
    EXPECT_EQ(holding_outputs, 1) << "slave " << s << ": outputs whole in one piece";
    EXPECT_EQ(holding_inputs, 1) << "slave " << s << ": inputs whole in one piece";
  }
  const unsigned total = std::accumulate(pieces.begin(), pieces.end(), 0u,
                                         [](unsigned sum, const LrwPiece& p) { return sum + p.expected_wkc; });
  EXPECT_EQ(total, 3 * n) << "uncut windows: the pieces add up to one LRW over the image";
}

TEST(LrwSplit, EachPieceExpectsTheSlavesWhoseWindowsItCovers) {
  // Four slaves, 4 output and 2 input bytes each: outputs at 0-15, inputs at 16-23. Pieces of at
  // most 10 bytes, each cut at the furthest window edge that fits: [0,8) outputs of slaves 0 and 1,
  // [8,18) outputs of 2 and 3 and inputs of 0, [18,24) inputs of 1, 2 and 3.
  const auto slaves = line_of(4, 4, 2);
  const auto pieces = split_process_image(0, 24, slaves, 10);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].bytes, 8);
  EXPECT_EQ(pieces[0].expected_wkc, 4) << "outputs of slaves 0 and 1";
  EXPECT_EQ(pieces[1].bytes, 10);
  EXPECT_EQ(pieces[1].expected_wkc, 5) << "outputs of slaves 2 and 3, inputs of slave 0";
  EXPECT_EQ(pieces[2].bytes, 6);
  EXPECT_EQ(pieces[2].expected_wkc, 3) << "inputs of slaves 1-3";
  // A slave with inputs only, one with outputs only.
  const std::vector<SlaveImage> mixed{{0, 0, 6, 4}, {0, 6, 0, 0}};
  EXPECT_EQ(lrw_expected_wkc(0, 10, mixed), 3);
  EXPECT_EQ(lrw_expected_wkc(0, 6, mixed), 2);
  EXPECT_EQ(lrw_expected_wkc(6, 4, mixed), 1);
  EXPECT_EQ(lrw_expected_wkc(10, 4, mixed), 0);
}

TEST(LrwSplit, AWindowLongerThanAPieceIsCutWhereItMust) {
  const std::vector<SlaveImage> big{{0, 3000, 3000, 10}};
  const auto pieces = split_process_image(0, 3010, big, CycleFrames::kMaxLrwBytes);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0].bytes, CycleFrames::kMaxLrwBytes);
  EXPECT_EQ(pieces[0].expected_wkc, 2);
  EXPECT_EQ(pieces[1].bytes, CycleFrames::kMaxLrwBytes);
  EXPECT_EQ(pieces[1].expected_wkc, 2);
  EXPECT_EQ(pieces[2].bytes, 3010 - 2 * CycleFrames::kMaxLrwBytes);
  EXPECT_EQ(pieces[2].expected_wkc, 3) << "the rest of the outputs and the inputs";
}

TEST(LrwSplit, WithoutSlavesCutsEveryMaxBytesAndExpectsNothing) {
  const auto pieces = split_process_image(0, 3000, {}, 1000);
  ASSERT_EQ(pieces.size(), 3u);
  for (const LrwPiece& p : pieces) {
    EXPECT_EQ(p.bytes, 1000);
    EXPECT_EQ(p.expected_wkc, 0);
  }
  EXPECT_TRUE(split_process_image(0, 0, {}, 1000).empty());
}

TEST(CycleFramesTest, FrameZeroCarriesDcAndAlDatagramsAndEveryFrameFits) {
  const auto slaves = line_of(100, 25, 43);
  const std::uint32_t size = 100 * (25 + 43);
  CycleFrames frames(kDefaultMasterMac, split_process_image(0, size, slaves, CycleFrames::kMaxLrwBytes), 0x1001, 100);
  ASSERT_GE(frames.count(), 5u);
  EXPECT_EQ(frames.image_bytes(), size);
  const std::vector<std::uint8_t> image(size, 0x5A);
  frames.build(image, 250, static_cast<std::uint16_t>(AlState::Op));
  std::vector<int> seen(256, 0);
  for (std::size_t i = 0; i < frames.count(); ++i) {
    const Frame& f = frames.frames()[i];
    EXPECT_LE(f.bytes().size(), Frame::kMaxFrameBytes);
    EXPECT_EQ(f.datagram_count(), i == 0 ? 4u : 1u) << "frame " << i;
    EXPECT_EQ(f.data(0).size(), frames.pieces()[i].bytes) << "its LRW carries its piece";
    EXPECT_EQ(f.data(0)[0], 0x5A);
    for (std::size_t d = 0; d < f.datagram_count(); ++d) ++seen[f.index(d)];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(frames.count() + 3)) << "one index per datagram";
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 0), static_cast<long>(256 - frames.count() - 3));
  EXPECT_EQ(frames.indexes_per_cycle(), frames.count() + 3);
  // Without AL control and DC: LRW and BRD only.
  CycleFrames plain(kDefaultMasterMac, split_process_image(0, size, slaves, CycleFrames::kMaxLrwBytes), 0, 100);
  plain.build(image, 0);
  EXPECT_EQ(plain.frames()[0].datagram_count(), 2u);
}

TEST(CycleFramesTest, NoProcessDataStillSendsFrameZero) {
  CycleFrames frames(kDefaultMasterMac, {}, 0x1001, 3);
  ASSERT_EQ(frames.count(), 1u);
  frames.build({}, 7);
  EXPECT_EQ(frames.frames()[0].datagram_count(), 2u) << "FRMW and BRD";
  EXPECT_TRUE(frames.lrw_ok(0));
}

TEST(CycleFramesTest, RefusesMoreThanItCanTell) {
  std::vector<LrwPiece> too_many(CycleFrames::kMaxFrames + 1, LrwPiece{0, 0, 1, 0});
  EXPECT_THROW(CycleFrames(kDefaultMasterMac, too_many, 0, 0), std::invalid_argument);
  const std::vector<LrwPiece> too_long{LrwPiece{0, 0, static_cast<std::uint16_t>(CycleFrames::kMaxLrwBytes + 1), 0}};
  EXPECT_THROW(CycleFrames(kDefaultMasterMac, too_long, 0, 0), std::invalid_argument);
}

}  // namespace
}  // namespace vdrive::master
