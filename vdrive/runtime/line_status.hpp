#pragma once
// LineStatus: what a status line shows of a served line (per slave: AL status, AL status code,
// the ESC's receive error counters, a drive's 603Fh and which alarm it is), written by the event loop's thread and read by another
// (`vdrive run`'s status line). Fixed size, one 64-bit atomic per slave so each slave reads
// consistently: no lock, no allocation on the loop. LineStatusPublisher is the writing side, a
// LoopService that samples the ESCs a few times a second and passes poll() on to the service it
// wraps. format_status_line() turns two samples into the line.
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/runtime/host_stalls.hpp"
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
  std::int16_t alarm = -1;           // the drive's newest active alarm: its index in the product's alarm table, -1 none
  std::uint16_t station = 0;         // register 0x0010: the station address the master set (0: none yet)
};

// Frames a wire fault (`vdrive fault inject drop|corrupt ...`, fault::WireImpairment between the
// master and slave 1) kept from their receiver, both directions together: dropped, and corrupted
// (sent on with a bad FCS, which the receiver discards).
struct WireLosses {
  std::uint64_t dropped = 0;
  std::uint64_t corrupted = 0;
};

class LineStatus {
public:
  explicit LineStatus(std::size_t slaves) : slaves_(slaves < kMaxStatusSlaves ? slaves : kMaxStatusSlaves) {}
  // A line served behind a wire fault stage: its losses are part of the status.
  void publish_wire(const WireLosses& w) {
    wire_dropped_.store(w.dropped, std::memory_order_relaxed);
    wire_corrupted_.store(w.corrupted, std::memory_order_relaxed);
    has_wire_.store(true, std::memory_order_release);
  }
  std::optional<WireLosses> wire() const {
    if (!has_wire_.load(std::memory_order_acquire)) return std::nullopt;
    return WireLosses{wire_dropped_.load(std::memory_order_relaxed), wire_corrupted_.load(std::memory_order_relaxed)};
  }
  std::size_t slaves() const { return slaves_; }
  // When the slaves were last published, on the loop's clock (so a reader can tell whether a
  // host stall came just before what it shows).
  void publish_time(Nanos now) { sampled_at_.store(now, std::memory_order_relaxed); }
  Nanos sampled_at() const { return sampled_at_.load(std::memory_order_relaxed); }
  void publish(std::size_t i, const SlaveStatus& s) {
    packed_[i].store(std::uint64_t{s.al_status} | std::uint64_t{s.al_status_code} << 16 | std::uint64_t{s.rx_errors} << 32,
                     std::memory_order_relaxed);
    error_codes_[i].store(std::uint64_t{s.error_code} | std::uint64_t{static_cast<std::uint16_t>(s.alarm + 1)} << 16 |
                              std::uint64_t{s.station} << 32,
                          std::memory_order_relaxed);
  }
  SlaveStatus slave(std::size_t i) const {
    const std::uint64_t v = packed_[i].load(std::memory_order_relaxed);
    const std::uint64_t drive = error_codes_[i].load(std::memory_order_relaxed);
    return {static_cast<std::uint16_t>(v), static_cast<std::uint16_t>(v >> 16), static_cast<std::uint32_t>(v >> 32),
            static_cast<std::uint16_t>(drive), static_cast<std::int16_t>(static_cast<int>((drive >> 16) & 0xFFFF) - 1),
            static_cast<std::uint16_t>(drive >> 32)};
  }

private:
  std::size_t slaves_;
  std::array<std::atomic<std::uint64_t>, kMaxStatusSlaves> packed_{};
  // 603Fh | (alarm index + 1) << 16 | station address << 32, read together; 0 (never published) is
  // "no alarm".
  std::array<std::atomic<std::uint64_t>, kMaxStatusSlaves> error_codes_{};
  std::atomic<std::uint64_t> wire_dropped_{0}, wire_corrupted_{0};
  std::atomic<bool> has_wire_{false};
  std::atomic<Nanos> sampled_at_{0};
};

// Slave `i` as the status line shows it (side-effect-free peeks of its ESC, its drive's 603Fh);
// on the loop's thread.
SlaveStatus slave_status(network::Network& network, std::size_t i);

// Reads the ESCs (side-effect-free peeks) every `period` on the loop's thread.
class LineStatusPublisher final : public LoopService {
public:
  LineStatusPublisher(network::Network& network, LineStatus& status, Nanos period, LoopService* next = nullptr)
      : network_(network), status_(status), period_(period), next_(next) {}
  void poll(Nanos now) override;
  Nanos next_deadline() const override;
  // Samples now, whatever the period (also done by the first poll()).
  void sample();
  // Where the wire fault stage's losses are read, on the loop's thread with the ESCs (this layer
  // does not see the fault layer; `vdrive run` reads its fault::WireImpairment). Set before the
  // loop starts; must not allocate.
  void set_wire_source(std::function<WireLosses()> source) { wire_source_ = std::move(source); }

private:
  network::Network& network_;
  LineStatus& status_;
  Nanos period_;
  LoopService* next_;
  Nanos due_ = 0;
  std::function<WireLosses()> wire_source_;
};

// One reading of everything the line shows, taken by the status thread.
struct StatusSample {
  Nanos time = 0;  // when it was taken (any monotonic clock)
  std::vector<SlaveStatus> slaves;
  std::uint64_t frames_in = 0, frames_out = 0, dropped = 0, send_failed = 0;
  std::optional<WireLosses> wire;  // none: no wire fault stage
  struct Onward {
    bool link = false;
    std::uint64_t sent = 0, returned = 0;
  };
  std::optional<Onward> onward;  // none: the line ends in this process
  // Host stalls (host_stalls.hpp): how many, the longest, and the latest if it ended at most
  // kStallAftermath before the slaves were sampled (a fault seen now follows it).
  std::uint64_t host_stalls = 0;
  Nanos longest_stall = 0;
  std::optional<HostStall> recent_stall;
};
StatusSample take_sample(const LineStatus& status, const LoopCounters& counters, Nanos now);

// "3 slaves 1:Op 2:Op 3:SafeOp+E(001B) | frames 5210 in 5210 out, 1000/s | rx errors 0 | dropped 0 | send failed 0
// | wire fault dropped 0 corrupted 0 | onward up, 5210 on, 5210 back | host stalls 2, longest 12.3 ms"
// (the wire part only with a wire fault stage, the onward part only where the line goes on beyond
// this process, the stalls only after one);
// the rate is frames in per second since `before` (none when there is no earlier sample). With
// more than 8 slaves the states are counted instead ("40 slaves Op 39, SafeOp+E 1 (first: 7 001B)").
std::string format_status_line(const StatusSample& now, const StatusSample* before);
// "Init", "PreOp", "Boot", "SafeOp", "Op", or "0x5" for a value no state has.
std::string al_state_name(std::uint16_t al_status);

}  // namespace vdrive::runtime
