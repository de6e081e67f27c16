#pragma once
// The CiA 402 objects the engine itself reads (commands) and writes (actual values) every control
// step, resolved once. Objects a product lacks are absent handles (ObjectRef).
#include <cstdint>

#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

struct AxisObjects {
  explicit AxisObjects(od::ObjectStore& s)
      : controlword(s, 0x6040), statusword(s, 0x6041), error_code(s, 0x603F),
        position_demand(s, 0x6062), position_internal(s, 0x6063), position_actual(s, 0x6064),
        velocity_demand(s, 0x606B), velocity_actual(s, 0x606C), torque_demand(s, 0x6074),
        torque_actual(s, 0x6077), current_actual(s, 0x6078), dc_link_voltage(s, 0x6079),
        following_error(s, 0x60F4), control_effort(s, 0x60FA), position_demand_internal(s, 0x60FC),
        home_offset(s, 0x607C), polarity(s, 0x607E), max_torque(s, 0x6072), max_motor_speed(s, 0x6080),
        positive_torque_limit(s, 0x60E0), negative_torque_limit(s, 0x60E1),
        soft_limit_min(s, 0x607D, 1), soft_limit_max(s, 0x607D, 2), range_min(s, 0x607B, 1),
        range_max(s, 0x607B, 2), rated_current(s, 0x6075), rated_torque(s, 0x6076),
        encoder_increments(s, 0x608F, 1), encoder_revolutions(s, 0x608F, 2), gear_motor(s, 0x6091, 1),
        gear_shaft(s, 0x6091, 2), feed(s, 0x6092, 1), feed_shaft(s, 0x6092, 2) {}

  ObjectRef<std::uint16_t> controlword, statusword, error_code;
  ObjectRef<std::int32_t> position_demand, position_internal, position_actual;
  ObjectRef<std::int32_t> velocity_demand, velocity_actual;
  ObjectRef<std::int16_t> torque_demand, torque_actual, current_actual;
  ObjectRef<std::uint32_t> dc_link_voltage;
  ObjectRef<std::int32_t> following_error, control_effort, position_demand_internal;
  ObjectRef<std::int32_t> home_offset;
  ObjectRef<std::uint8_t> polarity;
  ObjectRef<std::uint16_t> max_torque;
  ObjectRef<std::uint32_t> max_motor_speed;
  ObjectRef<std::uint16_t> positive_torque_limit, negative_torque_limit;
  ObjectRef<std::int32_t> soft_limit_min, soft_limit_max, range_min, range_max;
  ObjectRef<std::uint32_t> rated_current, rated_torque;
  ObjectRef<std::uint32_t> encoder_increments, encoder_revolutions, gear_motor, gear_shaft, feed, feed_shaft;
};

}  // namespace vdrive::drive
