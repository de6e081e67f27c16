#pragma once
// LineStatus: what a status line shows of a served line (per slave: AL status, AL status code,
// the ESC's receive error counters, a drive's 603Fh), written by the event loop's thread and read by another
// (`vdrive run`'s status line). Fixed size, one 64-bit atomic per slave so each slave reads
// consistently: no lock, no allocation on the loop. LineStatusPublisher is the writing side, a
// LoopService that samples the ESCs a few times a second and passes poll() on to the service it
// wraps. format_status_line() turns two samples into the line.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/loop_service.hpp"

namespace vdrive::network {
class Network;
}

namespace vdrive::runtime {

inline constexpr std::size_t kMaxStatusSlaves = 64;  // slaves beyond it are not shown

struct SlaveStatus {
  std::uint16_t al_status = 0;       // register 0x0130: state in bits 0-3, error flag bit 4
  std::uint16_t al_status_code = 0;  // register 0x0134
  std::uint32_t rx_errors = 0;       // sum of the error counters 0x0300-0x030C (invalid frames, RX, forwarded, processing unit)
  std::uint16_t error_code = 0;      // 603Fh of a drive (0 for other slaves)
};

class LineStatus {
public:
  explicit LineStatus(std::size_t slaves) : slaves_(slaves < kMaxStatusSlaves ? slaves : kMaxStatusSlaves) {}
  std::size_t slaves() const { return slaves_; }
  void publish(std::size_t i, const SlaveStatus& s) {
    packed_[i].store(std::uint64_t{s.al_status} | std::uint64_t{s.al_status_code} << 16 | std::uint64_t{s.rx_errors} << 32,
                     std::memory_order_relaxed);
    error_codes_[i].store(s.error_code, std::memory_order_relaxed);
  }
  SlaveStatus slave(std::size_t i) const {
    const std::uint64_t v = packed_[i].load(std::memory_order_relaxed);
    return {static_cast<std::uint16_t>(v), static_cast<std::uint16_t>(v >> 16), static_cast<std::uint32_t>(v >> 32),
            error_codes_[i].load(std::memory_order_relaxed)};
  }

private:
  std::size_t slaves_;
  std::array<std::atomic<std::uint64_t>, kMaxStatusSlaves> packed_{};
  std::array<std::atomic<std::uint16_t>, kMaxStatusSlaves> error_codes_{};
};

// Reads the ESCs (side-effect-free peeks) every `period` on the loop's thread.
class LineStatusPublisher final : public LoopService {
public:
  LineStatusPublisher(network::Network& network, LineStatus& status, Nanos period, LoopService* next = nullptr)
      : network_(network), status_(status), period_(period), next_(next) {}
  void poll(Nanos now) override;
  Nanos next_deadline() const override;
  // Samples now, whatever the period (also done by the first poll()).
  void sample();

private:
  network::Network& network_;
  LineStatus& status_;
  Nanos period_;
  LoopService* next_;
  Nanos due_ = 0;
};

// One reading of everything the line shows, taken by the status thread.
struct StatusSample {
  Nanos time = 0;  // when it was taken (any monotonic clock)
  std::vector<SlaveStatus> slaves;
  std::uint64_t frames_in = 0, frames_out = 0, dropped = 0, send_failed = 0;
};
StatusSample take_sample(const LineStatus& status, const LoopCounters& counters, Nanos now);

// "3 slaves 1:Op 2:Op 3:SafeOp+E(001B) | frames 5210 in 5210 out, 1000/s | rx errors 0 | dropped 0 | send failed 0";
// the rate is frames in per second since `before` (none when there is no earlier sample). With
// more than 8 slaves the states are counted instead ("40 slaves Op 39, SafeOp+E 1 (first: 7 001B)").
std::string format_status_line(const StatusSample& now, const StatusSample* before);
// "Init", "PreOp", "Boot", "SafeOp", "Op", or "0x5" for a value no state has.
std::string al_state_name(std::uint16_t al_status);

}  // namespace vdrive::runtime
