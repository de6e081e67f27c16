#include "vdrive/drive/unit_scaling.hpp"

#include <numbers>

namespace vdrive::drive {

namespace {
double ratio(std::uint32_t num, std::uint32_t den) {
  // 0 is not a valid divisor or factor; the DS1000-EC reads 608Fh-01h = 0 as 2^32 (L1152).
  const double n = num == 0 ? 4294967296.0 : static_cast<double>(num);
  const double d = den == 0 ? 1.0 : static_cast<double>(den);
  return n / d;
}
}  // namespace

FactorGroup factor_group(const FactorObjects& o, std::uint32_t counts_per_rev) {
  auto at_least_one = [](std::uint32_t v) { return v == 0 ? 1u : v; };
  FactorGroup f;
  f.encoder_increments = o.encoder_increments != 0 ? o.encoder_increments : at_least_one(counts_per_rev);
  f.encoder_revolutions = at_least_one(o.encoder_revolutions);
  f.gear_motor_revolutions = at_least_one(o.gear_motor);
  f.gear_shaft_revolutions = at_least_one(o.gear_shaft);
  f.feed = o.has_feed ? at_least_one(o.feed) : f.encoder_increments;
  f.feed_shaft_revolutions = at_least_one(o.feed_shaft);
  f.polarity = o.polarity;
  return f;
}

void UnitScaling::apply(const FactorGroup& f, bool torque_follows_velocity) {
  f_ = f;
  inc_per_rev_ = ratio(f.encoder_increments, f.encoder_revolutions);
  const double motor_rev_per_user =
      ratio(f.gear_motor_revolutions, f.gear_shaft_revolutions) / ratio(f.feed, f.feed_shaft_revolutions);
  inc_per_user_ = inc_per_rev_ * motor_rev_per_user;
  rad_per_user_ = 2.0 * std::numbers::pi * motor_rev_per_user;
  pos_sign_ = (f.polarity & 0x80) ? -1.0 : 1.0;
  vel_sign_ = (f.polarity & 0x40) ? -1.0 : 1.0;
  torque_sign_ = torque_follows_velocity ? vel_sign_ : ((f.polarity & 0x20) ? -1.0 : 1.0);
}

double UnitScaling::rpm_to_user(double rpm) const { return rpm / 60.0 * 2.0 * std::numbers::pi / rad_per_user_; }

double UnitScaling::user_to_rpm(double user_s) const {
  return user_s * rad_per_user_ / (2.0 * std::numbers::pi) * 60.0;
}

}  // namespace vdrive::drive
