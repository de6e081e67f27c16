#pragma once
// A small SDO client for the tests, written from ETG.1000.6 independently of the server: it picks
// expedited / normal / segmented transfers by size and follows segments with the toggle bit.
#include <cstdint>
#include <vector>

#include "tests/firmware/mailbox_test_bench.hpp"

namespace vdrive::firmware::mailbox_test {

constexpr std::uint8_t kCoE = 3;

struct SdoResult {
  std::uint32_t abort = 0;           // 0: success
  std::vector<std::uint8_t> data;    // upload data
  bool expedited = false;
  int segments = 0;                  // segment exchanges the transfer took
};

inline std::vector<std::uint8_t> sdo_payload(std::uint8_t command, std::uint16_t index,
                                             std::uint8_t sub, std::vector<std::uint8_t> data = {}) {
  std::vector<std::uint8_t> p{0x00, 0x20, command, static_cast<std::uint8_t>(index),
                              static_cast<std::uint8_t>(index >> 8), sub};
  data.resize(std::max<std::size_t>(data.size(), 4), 0);
  p.insert(p.end(), data.begin(), data.end());
  return p;
}

inline bool is_abort(const std::vector<std::uint8_t>& r) {
  return r.size() >= 16 && (r[5] & 0x0F) == kCoE && r.at(8) == 0x80;
}

inline SdoResult sdo_read(Bench& b, std::uint16_t index, std::uint8_t sub, bool complete = false) {
  SdoResult out;
  auto r = b.exchange(kCoE, sdo_payload(complete ? 0x50 : 0x40, index, sub));
  if (!r) { ADD_FAILURE() << "no reply"; return out; }
  if (is_abort(*r)) { out.abort = u32_at(*r, 12); return out; }
  const std::uint8_t cmd = r->at(8);
  EXPECT_EQ(cmd >> 5, 2) << "initiate upload response";
  if (cmd & 0x02) {
    out.expedited = true;
    const std::size_t n = (cmd & 0x01) ? 4 - ((cmd >> 2) & 3) : 4;
    out.data.assign(r->begin() + 12, r->begin() + 12 + static_cast<std::ptrdiff_t>(n));
    return out;
  }
  const std::size_t size = u32_at(*r, 12);
  out.data.assign(r->begin() + 16, r->end());
  bool toggle = false;
  while (out.data.size() < size && out.segments < 10000) {
    auto s = b.exchange(kCoE, sdo_payload(static_cast<std::uint8_t>(0x60 | (toggle ? 0x10 : 0)), 0, 0));
    if (!s) { ADD_FAILURE() << "no segment reply"; return out; }
    if (is_abort(*s)) { out.abort = u32_at(*s, 12); return out; }
    const std::uint8_t sc = s->at(8);
    if ((sc >> 5) != 0) { ADD_FAILURE() << "not an upload segment response"; return out; }
    EXPECT_EQ((sc & 0x10) != 0, toggle);
    std::size_t n = s->size() - 9;
    if (u16_at(*s, 0) == 10) n = 7 - ((sc >> 1) & 7);
    out.data.insert(out.data.end(), s->begin() + 9, s->begin() + 9 + static_cast<std::ptrdiff_t>(n));
    ++out.segments;
    toggle = !toggle;
    if (sc & 0x01) break;
  }
  EXPECT_EQ(out.data.size(), size);
  return out;
}

inline SdoResult sdo_write(Bench& b, std::uint16_t index, std::uint8_t sub,
                           const std::vector<std::uint8_t>& data, bool complete = false) {
  SdoResult out;
  const std::uint8_t ca = complete ? 0x10 : 0x00;
  std::optional<std::vector<std::uint8_t>> r;
  std::size_t sent = data.size();
  if (data.size() <= 4 && !complete) {
    const auto cmd = static_cast<std::uint8_t>(0x23 | ((4 - data.size()) << 2));
    r = b.exchange(kCoE, sdo_payload(cmd, index, sub, data));
  } else {
    const std::size_t room = b.sm0_length() - 16u;
    sent = std::min(room, data.size());
    std::vector<std::uint8_t> p = sdo_payload(static_cast<std::uint8_t>(0x21 | ca), index, sub,
                                              {static_cast<std::uint8_t>(data.size()),
                                               static_cast<std::uint8_t>(data.size() >> 8),
                                               static_cast<std::uint8_t>(data.size() >> 16), 0});
    p.insert(p.end(), data.begin(), data.begin() + static_cast<std::ptrdiff_t>(sent));
    r = b.exchange(kCoE, p);
  }
  if (!r) { ADD_FAILURE() << "no reply"; return out; }
  if (is_abort(*r)) { out.abort = u32_at(*r, 12); return out; }
  EXPECT_EQ(r->at(8), 0x60) << "initiate download response";
  bool toggle = false;
  while (sent < data.size()) {
    const std::size_t room = b.sm0_length() - 9u;
    const std::size_t n = std::min(room, data.size() - sent);
    const bool last = sent + n == data.size();
    std::uint8_t cmd = static_cast<std::uint8_t>((toggle ? 0x10 : 0) | (last ? 0x01 : 0));
    std::vector<std::uint8_t> p{0x00, 0x20};
    if (n < 7) cmd |= static_cast<std::uint8_t>((7 - n) << 1);
    p.push_back(cmd);
    p.insert(p.end(), data.begin() + static_cast<std::ptrdiff_t>(sent),
             data.begin() + static_cast<std::ptrdiff_t>(sent + n));
    p.resize(std::max<std::size_t>(p.size(), 10), 0);
    auto s = b.exchange(kCoE, p);
    if (!s) { ADD_FAILURE() << "no segment reply"; return out; }
    if (is_abort(*s)) { out.abort = u32_at(*s, 12); return out; }
    EXPECT_EQ(s->at(8), 0x20 | (toggle ? 0x10 : 0)) << "download segment response";
    sent += n;
    ++out.segments;
    toggle = !toggle;
  }
  return out;
}

inline std::vector<std::uint8_t> le(std::uint64_t v, std::size_t n) {
  std::vector<std::uint8_t> b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(v >> (8 * i));
  return b;
}

}  // namespace vdrive::firmware::mailbox_test
