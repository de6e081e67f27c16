#include "master/lrw_split.hpp"

#include <algorithm>
#include <stdexcept>

namespace vdrive::master {
namespace {

bool overlaps(std::uint32_t a, std::uint32_t a_len, std::uint32_t b, std::uint32_t b_len) {
  return a_len != 0 && b_len != 0 && a < b + b_len && b < a + a_len;
}

}  // namespace

std::uint16_t lrw_expected_wkc(std::uint32_t logical, std::uint32_t bytes, std::span<const SlaveImage> slaves) {
  unsigned wkc = 0;
  for (const SlaveImage& s : slaves) {
    if (overlaps(logical, bytes, s.output_logical, s.output_bytes)) wkc += 2;
    if (overlaps(logical, bytes, s.input_logical, s.input_bytes)) wkc += 1;
  }
  return static_cast<std::uint16_t>(wkc);
}

std::vector<LrwPiece> split_process_image(std::uint32_t logical_start, std::uint32_t image_bytes,
                                          std::span<const SlaveImage> slaves, std::size_t max_bytes) {
  if (max_bytes == 0) throw std::invalid_argument("split_process_image: a piece must hold at least one byte");
  // Offsets (from the image's start) where a cut leaves every window whole.
  std::vector<std::uint32_t> edges;
  auto edge = [&](std::uint32_t logical, std::uint32_t length) {
    if (length == 0) return;
    for (const std::uint32_t at : {logical, logical + length}) {
      if (at > logical_start && at - logical_start < image_bytes) edges.push_back(at - logical_start);
    }
  };
  for (const SlaveImage& s : slaves) {
    edge(s.output_logical, s.output_bytes);
    edge(s.input_logical, s.input_bytes);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  std::vector<LrwPiece> pieces;
  std::uint32_t at = 0;
  while (at < image_bytes) {
    const std::uint32_t limit = static_cast<std::uint32_t>(std::min<std::size_t>(image_bytes, at + max_bytes));
    std::uint32_t cut = limit;
    if (limit < image_bytes) {
      // The furthest edge that still fits; none: a window longer than a piece is cut where it must.
      const auto after = std::upper_bound(edges.begin(), edges.end(), limit);
      if (after != edges.begin() && *std::prev(after) > at) cut = *std::prev(after);
    }
    LrwPiece p;
    p.logical = logical_start + at;
    p.offset = at;
    p.bytes = static_cast<std::uint16_t>(cut - at);
    p.expected_wkc = lrw_expected_wkc(p.logical, p.bytes, slaves);
    pieces.push_back(p);
    at = cut;
  }
  return pieces;
}

}  // namespace vdrive::master
