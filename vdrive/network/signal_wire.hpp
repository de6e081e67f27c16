#pragma once
// A wire between two signal points (signal_point.hpp), as a cable on a test bench: from a digital
// output to a digital input, from a PLC output to a drive's probe input or brake, from a drive's
// limit switch to an input terminal. After every firmware call the network copies the source's
// value to the target. Between two entries (same bit size) the bytes are copied as the firmware
// stores them; a plant connection is one bit: from an entry it takes "not zero", into an entry it
// writes 0 or 1.
#include <string>

#include "vdrive/network/signal_point.hpp"

namespace vdrive::network {

struct SignalWire {
  SignalPoint from, to;
  std::string name;             // for messages: "wires[0] (do 0x7000:1 -> di 0x6000:1)"
};

}  // namespace vdrive::network
