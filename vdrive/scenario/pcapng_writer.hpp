#pragma once
// Writes Ethernet frames to a pcapng file (one section, one Ethernet interface with nanosecond
// time stamps), as Wireshark/tshark read it. Each frame carries its direction in the EPB flags
// option: outbound = master to the line, inbound = back to the master. Time stamps are the
// scenario's clock (virtual time starts at 0, i.e. 1970-01-01).
#include <cstdint>
#include <fstream>
#include <span>
#include <string>

#include "common/clock.hpp"

namespace vdrive::scenario {

class PcapngWriter {
public:
  // Throws std::runtime_error naming the file if it cannot be created.
  explicit PcapngWriter(const std::string& path);
  void write(std::span<const std::uint8_t> frame, Nanos time, bool to_master);
  std::uint64_t frames() const { return frames_; }

private:
  std::ofstream out_;
  std::string path_;
  std::uint64_t frames_ = 0;
};

}  // namespace vdrive::scenario
