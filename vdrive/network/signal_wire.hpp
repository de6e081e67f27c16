#pragma once
// A wire between two slaves' object entries, as a cable from a digital output to a digital input
// (or to any entry of the same size) is on a test bench: after every firmware call the network
// copies the source entry's value, as its firmware stores it, into the target entry, so the input
// reports what the output drives. Both entries must exist and have the same bit size.
#include <cstddef>
#include <cstdint>
#include <string>

namespace vdrive::network {

struct WireEnd {
  std::size_t slave = 0;        // 0-based, in the order the network was given
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
};

struct SignalWire {
  WireEnd from, to;
  std::string name;             // for messages: "wires[0] (do 0x7000:1 -> di 0x6000:1)"
};

}  // namespace vdrive::network
