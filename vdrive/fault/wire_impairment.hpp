#pragma once
// WireImpairment: a bad cable between the master and slave 1, one queue per direction. Every
// frame offered with push() is, by the settings of its direction and a seeded generator:
//   drop       lost (counted, never comes out);
//   corrupt    comes out with its FCS wrong. Bytes stay as sent; the flag is the truth. A
//              receiver drops it: the master's NIC (pop without the flag discards it), or the
//              line, where ESCs count it instead of executing it. The caller passes a frame
//              travelling to_slaves with the flag to network::Segment::process_corrupted(),
//              which counts an invalid frame in slave 1 (0x0300) and forwarded RX errors
//              (0x0308+) in the slaves behind; it never reaches the master. A frame corrupted
//              to_master was executed by the line already and is lost only to the master;
//   duplicate  comes out twice, right after each other;
//   reorder    is held back and released right after the next frame offered in the same
//              direction (or at clear()); until then next_release() does not count it. While
//              one frame is held the next one is not held too;
//   delay      every frame comes out `delay` after it was offered, never before a frame offered
//              earlier in that direction (no overtaking on a cable).
// Decisions draw four numbers per push() from a splitmix64 generator seeded at construction, so
// the same seed and the same calls give the same frames, counters and times, whatever the
// settings. No clock is read: times are the `now` the caller passes.
// Storage (capacity frames of link::kMaxFrame bytes per direction, plus one held frame) is
// allocated in the constructor; push/pop only copy. A frame that finds its queue full, or is
// longer than link::kMaxFrame, is dropped and counted as dropped. Single-threaded.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/clock.hpp"

namespace vdrive::fault {

enum class Direction : std::uint8_t { to_slaves, to_master };

struct WireSettings {               // per direction; probabilities 0..1 (clamped)
  double drop = 0, corrupt = 0, duplicate = 0, reorder = 0;
  Nanos delay = 0;                  // every frame held this long (negative: 0)
};

class WireImpairment {
public:
  explicit WireImpairment(std::uint64_t seed, std::size_t capacity = 64);

  void set(Direction d, const WireSettings& s);
  const WireSettings& settings(Direction d) const { return dir(d).settings; }
  // All settings back to a clean wire; frames already held (delayed, reordered) still come out.
  void clear();

  // Offers one frame travelling in `d` at `now`.
  void push(Direction d, std::span<const std::uint8_t> frame, Nanos now);
  // Next frame due at or before `now` into `out` (give it link::kMaxFrame bytes; a shorter
  // buffer gets the frame cut); returns the bytes written, 0 if none is due. `fcs_error` says
  // whether the frame arrives with a bad FCS (corrupted).
  std::size_t pop(Direction d, std::span<std::uint8_t> out, Nanos now, bool& fcs_error);
  // The same as a receiver sees it: corrupted frames are discarded, only intact ones return.
  std::size_t pop(Direction d, std::span<std::uint8_t> out, Nanos now);
  // When the next frame comes out; INT64_MAX if none is queued (a reordered frame waiting for
  // its successor does not count).
  Nanos next_release(Direction d) const;

  struct Counters {
    std::uint64_t passed = 0;      // frames popped intact (each copy of a duplicate counts)
    std::uint64_t dropped = 0;     // lost: by `drop`, a full queue or an oversized frame
    std::uint64_t corrupted = 0;   // offered frames given a bad FCS
    std::uint64_t duplicated = 0;  // offered frames sent twice
    std::uint64_t reordered = 0;   // offered frames held back behind their successor
  };
  const Counters& counters(Direction d) const { return dir(d).counters; }

private:
  struct Slot {
    std::size_t length = 0;
    Nanos release = 0;
    bool fcs_error = false;
  };
  struct Held {                    // a reordered frame waiting for its successor
    bool present = false;
    bool duplicate = false;
    Slot slot;
    std::vector<std::uint8_t> bytes;
  };
  struct Queue {
    WireSettings settings;
    Counters counters;
    std::vector<std::uint8_t> bytes;  // capacity * kMaxFrame
    std::vector<Slot> slots;          // ring
    std::size_t head = 0, count = 0;
    Nanos last_release = INT64_MIN;
    Held held;
  };

  Queue& dir(Direction d) { return queues_[static_cast<std::size_t>(d)]; }
  const Queue& dir(Direction d) const { return queues_[static_cast<std::size_t>(d)]; }
  bool enqueue(Queue& q, std::span<const std::uint8_t> frame, Nanos release, bool fcs_error);
  void enqueue_copies(Queue& q, std::span<const std::uint8_t> frame, Nanos release, bool fcs_error,
                      bool duplicate);
  void release_held(Queue& q);
  double uniform();

  std::uint64_t state_;
  std::size_t capacity_;
  std::array<Queue, 2> queues_;
};

}  // namespace vdrive::fault
