// libFuzzer target: arbitrary bytes as whole Ethernet frames into a Network of the three products
// (segment, ESCs and their firmware), the exact path a frame from the wire takes in `vdrive run`.
//
// Input: records [flags(1) length(2, LE) frame(length)]. Flag bit 0 patches the EtherType to
// 0x88A4 and the EtherCAT header to a type-1 PDU of the record's length, so most inputs reach the
// datagram engine and the firmware; flags >> 1 is the virtual time (100 µs units) that passes
// before the next frame, so timers (SII busy, watchdogs, SYNC) run too. One network is reused
// across inputs, power-cycled before each, so every input starts from the same state.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "tests/fuzz/fuzz_records.hpp"
#include "vdrive/network/network.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::array<std::string, 3> kLine = {"a6b", "ds5c1", "ds1000a"};
  // Built once (profiles parse slowly); every input starts from a power cycle at time 0.
  static vdrive::VirtualClock clock;
  static vdrive::network::Network network(kLine, clock);
  clock.set(0);
  network.power_cycle(0);
  std::vector<std::uint8_t> frame;
  frame.reserve(1600);
  vdrive::fuzz::for_each_record(data, size, frame, [&](std::uint8_t flags) {
    if ((flags & 0x01) && frame.size() >= 16) {
      frame[12] = 0x88;
      frame[13] = 0xA4;
      const std::size_t body = frame.size() - 16;
      frame[14] = static_cast<std::uint8_t>(body);
      frame[15] = static_cast<std::uint8_t>(0x10 | ((body >> 8) & 0x07));
    }
    network.process_frame(frame, clock.now());
    clock.advance(static_cast<vdrive::Nanos>(flags >> 1) * 100'000);
    if (network.next_deadline() <= clock.now()) network.tick(clock.now());
  });
  return 0;
}
