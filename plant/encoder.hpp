#pragma once
// Motor-shaft encoder: quantises the continuous motor angle into counts, the way the drive reads it.
//  * counts = floor(theta / 2pi * counts_per_rev) (+ offset for incremental encoders, which count
//    from 0 at power-on).
//  * Absolute single-turn: only the position within the turn survives (0..cpr-1 per turn, turns
//    always read 0). Multi-turn with N bits: the turn counter wraps modulo 2^N (signed).
//  * Index: once per turn at index_angle; update() reports whether it passed and the count at it.
#include <cstdint>

#include "plant/plant_description.hpp"

namespace vdrive::plant {

struct EncoderReading {
  std::int64_t counts = 0;        // position as the drive sees it (single-turn + turns * cpr)
  std::uint32_t single_turn = 0;  // 0 .. cpr-1
  std::int32_t turns = 0;         // multi-turn counter (0 for single-turn encoders)
  bool index_passed = false;      // the index mark was crossed during the last update
  std::int64_t index_counts = 0;  // counts at the last index mark crossed
};

class Encoder {
public:
  Encoder(const EncoderSpec& spec, double initial_angle_rad);
  // New motor angle (continuous, rad); the reading reflects it.
  void update(double angle_rad);
  const EncoderReading& reading() const { return reading_; }
  // Raw count (continuous, before any wrap): floor(angle / 2pi * cpr).
  std::int64_t raw_counts(double angle_rad) const;

private:
  EncoderSpec spec_;
  std::int64_t offset_ = 0;  // subtracted from raw counts (incremental: power-on position)
  std::int64_t last_index_turn_ = 0;
  EncoderReading reading_;
};

}  // namespace vdrive::plant
