#pragma once
// As a master does at scan: an APWR of a station address to each position of a line served in
// process, first + 0, first + 1, ... in cable order.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/clock.hpp"
#include "ethercat/registers.hpp"
#include "tests/support/runtime_test_support.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::test {

// False if a slave did not take its address (working counter not 1). Call from the thread that
// serves `net`.
inline bool assign_station_addresses(network::Network& net, Nanos now, std::uint16_t first) {
  constexpr std::uint8_t kApwr = 0x02;
  for (std::size_t i = 0; i < net.size(); ++i) {
    const auto a = static_cast<std::uint16_t>(first + i);
    auto frame = ethercat_frame(kApwr, static_cast<std::uint16_t>(-static_cast<int>(i)), ecat::reg::kStationAddress,
                                std::vector<std::uint8_t>{static_cast<std::uint8_t>(a & 0xFF), static_cast<std::uint8_t>(a >> 8)});
    if (!net.process_frame(frame, now) || first_wkc(frame) != 1) return false;
  }
  return true;
}

}  // namespace vdrive::test
