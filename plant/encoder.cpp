#include "plant/encoder.hpp"

#include <cmath>

namespace vdrive::plant {

namespace {
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}
}  // namespace

Encoder::Encoder(const EncoderSpec& spec, double initial_angle_rad) : spec_(spec) {
  if (!spec_.absolute) offset_ = raw_counts(initial_angle_rad);
  last_index_turn_ =
      static_cast<std::int64_t>(std::floor((initial_angle_rad - spec_.index_angle_rad) / (2 * M_PI)));
  update(initial_angle_rad);
  reading_.index_passed = false;
}

std::int64_t Encoder::raw_counts(double angle_rad) const {
  return static_cast<std::int64_t>(std::floor(angle_rad / (2 * M_PI) * spec_.counts_per_rev));
}

void Encoder::update(double angle_rad) {
  const std::int64_t cpr = spec_.counts_per_rev;
  const std::int64_t c = raw_counts(angle_rad) - offset_;
  const std::int64_t turn = floor_div(c, cpr);
  reading_.single_turn = static_cast<std::uint32_t>(c - turn * cpr);
  if (spec_.absolute && spec_.multiturn_bits == 0) {
    reading_.turns = 0;
  } else if (spec_.absolute && spec_.multiturn_bits < 32) {
    const std::int64_t span = std::int64_t{1} << spec_.multiturn_bits;
    std::int64_t t = turn % span;
    if (t < 0) t += span;
    if (t >= span / 2) t -= span;  // signed turn counter
    reading_.turns = static_cast<std::int32_t>(t);
  } else {
    reading_.turns = static_cast<std::int32_t>(turn);
  }
  reading_.counts = std::int64_t{reading_.turns} * cpr + reading_.single_turn;

  // Index: the mark sits at index_angle + k * 2pi; crossing one changes this turn number.
  const auto index_turn =
      static_cast<std::int64_t>(std::floor((angle_rad - spec_.index_angle_rad) / (2 * M_PI)));
  reading_.index_passed = index_turn != last_index_turn_;
  if (reading_.index_passed) {
    // The mark crossed last: moving forward it is at the new turn's start, backward the old one's.
    const std::int64_t k = index_turn > last_index_turn_ ? index_turn : last_index_turn_;
    const double mark = spec_.index_angle_rad + 2 * M_PI * static_cast<double>(k);
    reading_.index_counts = std::llround(mark / (2 * M_PI) * static_cast<double>(cpr)) - offset_;
    last_index_turn_ = index_turn;
  }
}

}  // namespace vdrive::plant
