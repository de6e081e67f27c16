#include "vdrive/drive/io/digital_io.hpp"

#include "plant/plant.hpp"
#include "vdrive/drive/drive_types.hpp"

namespace vdrive::drive {
namespace {

constexpr std::uint32_t bit(unsigned n) { return std::uint32_t{1} << n; }

// 60FDh bit positions per product (see the header for the manual lines).
namespace a6b_in {
constexpr std::uint32_t ext1 = bit(19), ext2 = bit(20), inp = bit(24);
}
namespace ds5c1_in {
constexpr std::uint32_t probe1 = bit(3), probe2 = bit(4), z_output = bit(5);
}
namespace ds1000a_in {
constexpr std::uint32_t interlock = bit(3), in1 = bit(16), in2 = bit(17);
}
constexpr std::uint32_t kSetBrake = bit(0);  // 60FEh-01h bit 0 (A6B L28007-L28010, DS1000A-EC L3505)

// Limit bits at the positions CiA 402 gives them (0 negative, 1 positive, 2 home).
std::uint32_t limits_and_home(std::uint32_t detected, bool swap) {
  std::uint32_t out = 0;
  const bool pos = (detected & plant::input::positive_limit) != 0;
  const bool neg = (detected & plant::input::negative_limit) != 0;
  if (swap ? neg : pos) out |= din::positive_limit;
  if (swap ? pos : neg) out |= din::negative_limit;
  if (detected & plant::input::home) out |= din::home;
  return out;
}

}  // namespace

DigitalIo::DigitalIo(const DriveContext& ctx)
    : ctx_(ctx), logic_(ctx), digital_inputs_(ctx.objects, 0x60FD), physical_outputs_(ctx.objects, 0x60FE, 1),
      output_mask_(ctx.objects, 0x60FE, 2) {
  if (logic_.product() == IoProduct::DS5C1) z_hold_ms_ = ObjectRef<std::uint16_t>(ctx.objects, 0x2513, 0, 2);
  power_on();
}

void DigitalIo::power_on() {
  z_remaining_ns_ = 0;
  in_position_ = false;
  // DS1000A-EC: the outputs start at 60FEh-01h's initial value (set brake = 1, L3507) and a masked
  // bit keeps its state, so the brake stays engaged until the master unmasks bit 0 (L3517-L3524).
  outputs_ = logic_.product() == IoProduct::DS1000A ? physical_outputs_.get() : 0;
  take_outputs();
}

void DigitalIo::take_outputs() {
  const std::uint32_t value = physical_outputs_.get();
  const std::uint32_t mask = output_mask_.get();
  switch (logic_.product()) {
    case IoProduct::DS1000A: outputs_ = (outputs_ & ~mask) | (value & mask); break;
    case IoProduct::A6B:
      // A masked output is the drive's default 0 (L28090); for set brake that default is
      // "brake on" (L28118-L28167: bit mask 0 -> set brake = 1 in every communication state).
      outputs_ = (value & mask) | (mask & kSetBrake ? 0 : kSetBrake);
      break;
    case IoProduct::DS5C1:
    case IoProduct::Generic: outputs_ = value & mask; break;
  }
}

std::uint32_t DigitalIo::product_layout(std::uint32_t detected, bool swap_limits, bool index_output) const {
  const bool probe1 = (detected & plant::input::probe1) != 0;
  const bool probe2 = (detected & plant::input::probe2) != 0;
  switch (logic_.product()) {
    case IoProduct::A6B: {
      std::uint32_t v = limits_and_home(detected, swap_limits);  // 607Eh swaps POT/NOT (L28993-L29025)
      if (probe1) v |= a6b_in::ext1;
      if (probe2) v |= a6b_in::ext2;
      if (in_position_) v |= a6b_in::inp;
      return v;
    }
    case IoProduct::DS5C1: {
      std::uint32_t v = limits_and_home(detected, false);
      if (probe1) v |= ds5c1_in::probe1;
      if (probe2) v |= ds5c1_in::probe2;
      if (index_output) v |= ds5c1_in::z_output;
      return v;
    }
    case IoProduct::DS1000A: {
      std::uint32_t v = limits_and_home(detected, false);
      if (detected & din::torque_off) v |= ds1000a_in::interlock;  // 1 = TO input open (L3474)
      if (probe1) v |= ds1000a_in::in1;
      if (probe2) v |= ds1000a_in::in2;
      return v;
    }
    case IoProduct::Generic: return limits_and_home(detected, false);
  }
  return 0;
}

std::uint32_t DigitalIo::update(std::uint32_t plant_inputs, bool torque_off_input, bool index_crossed) {
  const std::uint32_t detected =
      logic_.detected((plant_inputs & ~din::torque_off) | (torque_off_input ? din::torque_off : 0u));

  // DS5C1 Z output: on when the encoder passes zero, off after P5-19 ms (L4771, L10239).
  const auto period = static_cast<std::int64_t>(ctx_.profile.drive.control_period_ns);
  if (index_crossed)
    z_remaining_ns_ = static_cast<std::int64_t>(z_hold_ms_.get()) * 1'000'000;
  const bool z_output = z_remaining_ns_ > 0;
  if (z_remaining_ns_ > 0) z_remaining_ns_ -= period;

  // The user frame: with the position polarity inverted, the user-positive end is the plant's
  // negative end.
  const bool inverted = ctx_.units.position_sign() < 0.0;
  digital_inputs_.set(product_layout(detected, inverted, z_output));
  take_outputs();

  std::uint32_t din_bits = limits_and_home(detected, inverted);
  if (detected & plant::input::probe1) din_bits |= din::probe1;
  if (detected & plant::input::probe2) din_bits |= din::probe2;
  if (torque_off_input && ctx_.profile.drive.torque_off_input) din_bits |= din::torque_off;
  return din_bits;
}

bool DigitalIo::brake_engaged(bool power_stage_on) const {
  switch (ctx_.profile.drive.brake) {
    case profile::BrakeRule::Automatic: return !power_stage_on;
    case profile::BrakeRule::Master: return (outputs_ & kSetBrake) != 0;
  }
  return true;
}

}  // namespace vdrive::drive
