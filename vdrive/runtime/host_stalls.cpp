// Host stalls: detection on the loop thread, the record ring, the text. See host_stalls.hpp.
#include "vdrive/runtime/host_stalls.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "ethercat/registers.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::runtime {
namespace {

constexpr std::size_t kMaxNamedSlaves = 64;  // the masks' width
constexpr std::uint16_t kOutputSync = 0x1C32;
constexpr std::uint8_t kCycleTime = 0x02, kSync0CycleTime = 0x0A;

bool cyclic(std::uint16_t al_status) {
  const unsigned state = al_status & 0x0F;
  return state == 4 || state == 8;  // Safe-Op, Op: the drive follows the master's cycle
}

// The cycle a slave in Safe-Op or Op runs at: its SYNC0 cycle in DC mode (1C32h-0Ah), else its
// SM2 cycle (1C32h-02h); 0 if neither is known. Dictionary look-ups, no allocation.
Nanos sync0_cycle(network::Network& network, std::size_t i) {
  return drive::ObjectRef<std::int64_t>(network.firmware(i).objects(), kOutputSync, kSync0CycleTime).get();
}

Nanos bus_cycle(network::Network& network, std::size_t i) {
  if (!cyclic(network.esc(i).peek_u16(ecat::reg::kAlStatus))) return 0;
  if (const Nanos dc = sync0_cycle(network, i); dc > 0) return dc;
  return drive::ObjectRef<std::int64_t>(network.firmware(i).objects(), kOutputSync, kCycleTime).get();
}

std::uint32_t periods(Nanos late, Nanos period) {
  return period > 0 ? static_cast<std::uint32_t>(std::min<Nanos>(1 + late / period, UINT32_MAX)) : 0;
}

// Appends to a fixed buffer, cutting at its end (fmt::format_to_n writes through a counting
// iterator: no allocation).
struct Text {
  std::span<char> out;
  std::size_t first = 1;  // the number of bit 0's slave
  std::size_t used = 0;
  template <typename... A> void add(fmt::format_string<A...> f, A&&... args) {
    if (used + 1 >= out.size()) return;
    const auto r = fmt::format_to_n(out.data() + used, out.size() - 1 - used, f, std::forward<A>(args)...);
    used += std::min(r.size, out.size() - 1 - used);
    out[used] = '\0';
  }
  // "1-3,5" (slaves from `first`)
  void slaves(std::uint64_t mask) {
    const char* sep = "";
    for (int i = 0; i < 64; ++i) {
      if (!(mask >> i & 1)) continue;
      int j = i;
      while (j + 1 < 64 && (mask >> (j + 1) & 1)) ++j;
      if (j == i) add("{}{}", sep, first + static_cast<std::size_t>(i));
      else add("{}{}-{}", sep, first + static_cast<std::size_t>(i), first + static_cast<std::size_t>(j));
      sep = ",";
      i = j;
    }
  }
};

}  // namespace

void HostStalls::look(network::Network& network, Nanos now) {
  HostStall s;
  s.time = now;
  s.length = now - planned_;
  const std::size_t n = network.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Nanos c = bus_cycle(network, i);
    if (c > 0 && (s.cycle == 0 || c < s.cycle)) s.cycle = c;
  }
  s.threshold = std::max(floor_.load(std::memory_order_relaxed), kStallCycles * s.cycle);
  if (s.length <= s.threshold) return;
  planned_ = kNever;  // one stall per plan
  for (std::size_t i = 0; i < std::min(n, kMaxNamedSlaves); ++i) {
    const std::uint64_t bit = std::uint64_t{1} << i;
    if (const Nanos c0 = sync0_cycle(network, i); c0 > 0 && cyclic(network.esc(i).peek_u16(ecat::reg::kAlStatus))) {
      if (const Nanos due = network.esc(i).next_deadline(); due <= now) {
        s.sync0_slaves |= bit;
        s.sync0_pulses = std::max(s.sync0_pulses, periods(now - due, c0));
      }
    }
    // Batched steps may wait that long by design; only what is later than that was the host's.
    const drive::DriveEngine* engine = network.firmware(i).drive();
    if (const Nanos due = engine != nullptr ? engine->next_step() + network.control_step_batch() : kNever; due <= now) {
      s.step_slaves |= bit;
      s.control_steps = std::max(s.control_steps, periods(now - due, engine->control_period()));
    }
  }
  record(s);
}

void HostStalls::record(HostStall s) {
  const std::uint64_t number = count_.load(std::memory_order_relaxed) + 1;
  s.number = number;
  Slot& slot = ring_[number % kLog];
  slot.number.store(0, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);  // the 0 is seen before any new field
  slot.time.store(s.time, std::memory_order_relaxed);
  slot.length.store(s.length, std::memory_order_relaxed);
  slot.threshold.store(s.threshold, std::memory_order_relaxed);
  slot.cycle.store(s.cycle, std::memory_order_relaxed);
  slot.sync0_slaves.store(s.sync0_slaves, std::memory_order_relaxed);
  slot.sync0_pulses.store(s.sync0_pulses, std::memory_order_relaxed);
  slot.step_slaves.store(s.step_slaves, std::memory_order_relaxed);
  slot.control_steps.store(s.control_steps, std::memory_order_relaxed);
  slot.number.store(number, std::memory_order_release);
  if (s.length > longest_.load(std::memory_order_relaxed)) longest_.store(s.length, std::memory_order_relaxed);
  count_.store(number, std::memory_order_release);
}

std::optional<HostStall> HostStalls::get(std::uint64_t number) const {
  const std::uint64_t count = this->count();
  if (number == 0 || number > count || count - number >= kLog) return std::nullopt;
  const Slot& slot = ring_[number % kLog];
  if (slot.number.load(std::memory_order_acquire) != number) return std::nullopt;
  HostStall s;
  s.number = number;
  s.time = slot.time.load(std::memory_order_relaxed);
  s.length = slot.length.load(std::memory_order_relaxed);
  s.threshold = slot.threshold.load(std::memory_order_relaxed);
  s.cycle = slot.cycle.load(std::memory_order_relaxed);
  s.sync0_slaves = slot.sync0_slaves.load(std::memory_order_relaxed);
  s.sync0_pulses = slot.sync0_pulses.load(std::memory_order_relaxed);
  s.step_slaves = slot.step_slaves.load(std::memory_order_relaxed);
  s.control_steps = slot.control_steps.load(std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_acquire);  // the fields are read before the check below
  if (slot.number.load(std::memory_order_relaxed) != number) return std::nullopt;  // rewritten meanwhile
  return s;
}

std::optional<HostStall> HostStalls::just_before(Nanos now) const {
  // A reader's `now` is often a sample the loop took a little earlier, and the loop may have
  // recorded further stalls since: the ones after `now` are not what the fault followed. Of those
  // before it, the longest is the one worth naming (a long stall is often followed by short ones
  // while the host is still busy).
  std::optional<HostStall> found;
  const std::uint64_t count = this->count();
  for (std::uint64_t n = count; n > 0 && count - n < kLog; --n) {
    const std::optional<HostStall> s = get(n);
    if (!s || s->time > now) continue;
    if (now - s->time > kStallAftermath) break;  // older records ended earlier still
    if (!found || s->length > found->length) found = s;
  }
  return found;
}

std::size_t describe(const HostStall& s, std::span<char> out, std::size_t slaves_before) {
  if (out.empty()) return 0;
  Text t{out, slaves_before + 1};
  out[0] = '\0';
  t.add("host stall {:.1f} ms (threshold {:.1f} ms)", static_cast<double>(s.length) / 1e6, static_cast<double>(s.threshold) / 1e6);
  if (s.sync0_slaves == 0 && s.step_slaves == 0) {
    t.add(": the line's timers ran late");
    return t.used;
  }
  t.add(": ");
  if (s.sync0_slaves != 0) {
    t.add("slave{} ", (s.sync0_slaves & (s.sync0_slaves - 1)) != 0 ? "s" : "");
    t.slaves(s.sync0_slaves);
    if (s.sync0_pulses > 1) t.add(" missed {} SYNC0 pulse{}", s.sync0_pulses - 1, s.sync0_pulses > 2 ? "s" : "");
    else t.add(" got SYNC0 late");
  }
  if (s.step_slaves != 0) {
    if (s.sync0_slaves == s.step_slaves) t.add(" and");
    else {
      if (s.sync0_slaves != 0) t.add(",");
      t.add("{}drive{} ", s.sync0_slaves != 0 ? " " : "", (s.step_slaves & (s.step_slaves - 1)) != 0 ? "s" : "");
      t.slaves(s.step_slaves);
    }
    t.add(" caught up {} control step{}", s.control_steps, s.control_steps == 1 ? "" : "s");
  }
  return t.used;
}

std::string describe(const HostStall& stall, std::size_t slaves_before) {
  std::array<char, 256> buf{};
  const std::size_t n = describe(stall, buf, slaves_before);
  return std::string(buf.data(), n);
}

std::string stall_ms(Nanos length) { return fmt::format("{:.1f} ms", static_cast<double>(length) / 1e6); }

std::string after_stall(const std::optional<HostStall>& stall) {
  return stall ? " after a host stall of " + stall_ms(stall->length) : std::string();
}

}  // namespace vdrive::runtime
