#include "master/frame.hpp"

#include <algorithm>
#include <cstring>

#include "vdrive/link/link.hpp"

namespace vdrive::master {

namespace {
void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint16_t get16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
}  // namespace

Frame::Frame(const MacAddress& source) {
  std::copy(kBroadcastMac.begin(), kBroadcastMac.end(), buf_.begin());
  std::copy(source.begin(), source.end(), buf_.begin() + 6);
  buf_[12] = static_cast<std::uint8_t>(link::kEtherTypeEtherCat >> 8);
  buf_[13] = static_cast<std::uint8_t>(link::kEtherTypeEtherCat & 0xFF);
  clear();
}

void Frame::clear() {
  count_ = 0;
  size_ = kEthernetHeaderSize + kEtherCatHeaderSize;
  finish_header();
}

void Frame::finish_header() {
  const auto length = static_cast<std::uint16_t>(size_ - kEthernetHeaderSize - kEtherCatHeaderSize);
  put16(&buf_[kEthernetHeaderSize], static_cast<std::uint16_t>((length & kDatagramLengthMask) | 0x1000));
}

int Frame::add(Command cmd, std::uint8_t index, std::uint32_t address, std::uint16_t length) {
  if (count_ == kMaxDatagrams || length > kDatagramLengthMask) return -1;
  const std::size_t needed = kDatagramHeaderSize + length + kWkcSize;
  if (size_ + needed > kMaxFrameBytes) return -1;
  // The previous datagram now has a successor.
  if (count_ > 0) {
    std::uint8_t* prev = &buf_[slots_[count_ - 1].offset];
    put16(prev + 6, static_cast<std::uint16_t>(get16(prev + 6) | kDatagramMoreFollows));
  }
  std::uint8_t* d = &buf_[size_];
  d[0] = static_cast<std::uint8_t>(cmd);
  d[1] = index;
  put32(d + 2, address);
  put16(d + 6, length);
  put16(d + 8, 0);  // IRQ
  std::memset(d + kDatagramHeaderSize, 0, length + kWkcSize);
  slots_[count_] = Slot{size_, length, index, cmd};
  size_ += needed;
  finish_header();
  return static_cast<int>(count_++);
}

int Frame::add(Command cmd, std::uint8_t index, std::uint32_t address, std::span<const std::uint8_t> data) {
  if (data.size() > kDatagramLengthMask) return -1;
  const int slot = add(cmd, index, address, static_cast<std::uint16_t>(data.size()));
  if (slot >= 0 && !data.empty()) {
    std::memcpy(&buf_[slots_[static_cast<std::size_t>(slot)].offset + kDatagramHeaderSize], data.data(), data.size());
  }
  return slot;
}

bool Frame::accept_reply(std::span<const std::uint8_t> reply) {
  // The reply must carry exactly our datagrams: same commands, indexes and lengths in place.
  if (reply.size() < size_ || count_ == 0) return false;
  if (reply[12] != buf_[12] || reply[13] != buf_[13]) return false;  // EtherType 0x88A4
  const std::uint16_t ecat = get16(&reply[kEthernetHeaderSize]);
  if ((ecat >> 12) != 1) return false;
  if ((ecat & kDatagramLengthMask) != size_ - kEthernetHeaderSize - kEtherCatHeaderSize) return false;
  for (std::size_t i = 0; i < count_; ++i) {
    const Slot& s = slots_[i];
    const std::uint8_t* d = &reply[s.offset];
    if (d[0] != static_cast<std::uint8_t>(s.cmd) || d[1] != s.index) return false;
    if ((get16(d + 6) & kDatagramLengthMask) != s.length) return false;
  }
  // Keep our Ethernet header; take the rest from the reply.
  std::memcpy(&buf_[kEthernetHeaderSize], &reply[kEthernetHeaderSize], size_ - kEthernetHeaderSize);
  return true;
}

std::span<const std::uint8_t> Frame::data(std::size_t slot) const {
  const Slot& s = slots_[slot];
  return {&buf_[s.offset + kDatagramHeaderSize], s.length};
}

std::uint16_t Frame::wkc(std::size_t slot) const {
  const Slot& s = slots_[slot];
  return get16(&buf_[s.offset + kDatagramHeaderSize + s.length]);
}

}  // namespace vdrive::master
