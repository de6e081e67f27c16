#pragma once
// One EtherCAT frame under construction or as it came back: Ethernet header (broadcast
// destination, locally administered source, EtherType 0x88A4), EtherCAT header, then up to
// kMaxDatagrams datagrams, each with its own index. Fixed-size storage: building and parsing a
// frame allocates nothing.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "master/datagram.hpp"

namespace vdrive::master {

using MacAddress = std::array<std::uint8_t, 6>;
constexpr MacAddress kBroadcastMac{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
constexpr MacAddress kDefaultMasterMac{0x02, 0x00, 0x00, 0x00, 0x00, 0x01};

class Frame {
public:
  static constexpr std::size_t kMaxDatagrams = 16;
  static constexpr std::size_t kMaxFrameBytes = 1514;

  explicit Frame(const MacAddress& source = kDefaultMasterMac);

  // Drops all datagrams; the Ethernet header stays.
  void clear();

  // Appends a datagram whose data field is `data` (writes) or `length` zero bytes (reads).
  // Returns the datagram's slot (0..count-1), or -1 if it does not fit in the frame.
  int add(Command cmd, std::uint8_t index, std::uint32_t address, std::span<const std::uint8_t> data);
  int add(Command cmd, std::uint8_t index, std::uint32_t address, std::uint16_t length);

  std::size_t datagram_count() const { return count_; }
  std::uint8_t index(std::size_t slot) const { return slots_[slot].index; }
  // The frame as it goes on the wire (no padding: the link or kernel pads short frames).
  std::span<const std::uint8_t> bytes() const { return {buf_.data(), size_}; }

  // Takes `reply` as the answer to this frame if it has the same datagram layout (commands,
  // indexes, lengths); then data() and wkc() read the reply. Returns false (frame unchanged)
  // for anything else: other traffic, a malformed frame, or the reply to another frame.
  bool accept_reply(std::span<const std::uint8_t> reply);

  std::span<const std::uint8_t> data(std::size_t slot) const;
  std::uint16_t wkc(std::size_t slot) const;

private:
  struct Slot {
    std::size_t offset = 0;   // of the datagram header in buf_
    std::uint16_t length = 0; // data bytes
    std::uint8_t index = 0;
    Command cmd = Command::NOP;
  };
  void finish_header();

  std::array<std::uint8_t, kMaxFrameBytes> buf_{};
  std::size_t size_ = 0;
  std::array<Slot, kMaxDatagrams> slots_{};
  std::size_t count_ = 0;
};

}  // namespace vdrive::master
