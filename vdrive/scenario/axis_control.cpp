#include "vdrive/scenario/axis_control.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "ethercat/pdo_mapping_entry.hpp"
#include "master/master.hpp"
#include "master/process_data.hpp"

namespace vdrive::scenario {
namespace {

constexpr std::uint32_t entry(std::uint16_t index, std::uint8_t sub, std::uint8_t bits) {
  return ecat::PdoMappingEntry::encode(index, sub, bits);
}
constexpr std::uint32_t kOutputs[] = {entry(0x6040, 0, 16), entry(0x6060, 0, 8), entry(0x607A, 0, 32),
                                      entry(0x60FF, 0, 32), entry(0x6071, 0, 16)};
constexpr std::uint32_t kInputs[] = {entry(0x6041, 0, 16), entry(0x6061, 0, 8),  entry(0x6064, 0, 32),
                                     entry(0x606C, 0, 32), entry(0x6077, 0, 16), entry(0x60F4, 0, 32),
                                     entry(0x603F, 0, 16)};
constexpr std::uint16_t kRxPdo[] = {0x1600};
constexpr std::uint16_t kTxPdo[] = {0x1A00};

// Controlword commands and statusword states (CiA 402).
namespace cw {
constexpr std::uint16_t shutdown = 0x0006, switch_on = 0x0007, enable = 0x000F, fault_reset = 0x0080;
constexpr std::uint16_t new_set_point = 1u << 4, relative = 1u << 6;
}
constexpr std::uint16_t kSetPointAck = 1u << 12;
constexpr std::int8_t kPp = 1;

bool faulted(std::uint16_t s) { return (s & 0x0008) != 0; }
bool operation_enabled(std::uint16_t s) { return (s & 0x006F) == 0x0027; }


}  // namespace

void AxisControl::map_pdos(master::Master& m, std::size_t slave) {
  master::SdoClient& sdo = m.sdo(slave);
  master::assign_pdos(sdo, 0x1C12, {});
  master::assign_pdos(sdo, 0x1C13, {});
  master::map_pdo(sdo, 0x1600, kOutputs);
  master::map_pdo(sdo, 0x1A00, kInputs);
  master::assign_pdos(sdo, 0x1C12, kRxPdo);
  master::assign_pdos(sdo, 0x1C13, kTxPdo);
}

bool AxisControl::locate(const master::SlaveProcessData& pd, std::uint32_t out, std::uint32_t in, std::size_t size) {
  const long o[] = {master::pdo_entry_offset(pd.outputs, out, 0x6040), master::pdo_entry_offset(pd.outputs, out, 0x6060), master::pdo_entry_offset(pd.outputs, out, 0x607A),
                    master::pdo_entry_offset(pd.outputs, out, 0x60FF), master::pdo_entry_offset(pd.outputs, out, 0x6071), master::pdo_entry_offset(pd.inputs, in, 0x6041),
                    master::pdo_entry_offset(pd.inputs, in, 0x6064)};
  mapped_ = std::all_of(std::begin(o), std::end(o), [&](long v) { return v >= 0 && static_cast<std::size_t>(v) + 2 <= size; });
  if (!mapped_) return false;
  cw_ = o[0], mode_ = o[1], target_position_ = o[2], target_velocity_ = o[3], target_torque_ = o[4];
  status_at_ = o[5], position_at_ = o[6];
  return true;
}

void AxisControl::enable(std::int8_t mode) {
  mode_value_ = mode;
  power_ = Power::enabling;
}

void AxisControl::disable() {
  power_ = Power::disabling;
  motion_.reset();
}

void AxisControl::set_controlword(std::uint16_t value) {
  power_ = Power::manual;
  controlword_ = value;
}

void AxisControl::set_mode(std::int8_t mode) { mode_value_ = mode; }

void AxisControl::set_target(const TargetAction& t) {
  motion_.reset();
  if (t.position) {
    position_target_ = *t.position;
    tracking_ = false;
    relative_ = t.relative;
    if (mode_value_ == kPp) set_point_pending_ = true;
  }
  if (t.velocity) velocity_target_ = *t.velocity;
  if (t.torque) torque_target_ = *t.torque;
}

void AxisControl::start_motion(const MotionAction& m, Nanos now) {
  motion_ = m;
  motion_start_ = now;
  motion_origin_ = tracking_ ? position_ : position_target_;
  tracking_ = false;
}

void AxisControl::outputs(std::span<std::uint8_t> image, Nanos now) {
  if (!mapped_) return;
  std::uint16_t c = controlword_;
  switch (power_) {
    case Power::manual: break;
    case Power::enabling:
      if (faulted(status_)) c = last_cw_ == cw::fault_reset ? 0 : cw::fault_reset;  // a 0->1 edge of bit 7
      else if ((status_ & 0x004F) == 0x0040) c = cw::shutdown;                        // switch on disabled
      else if ((status_ & 0x006F) == 0x0021) c = cw::switch_on;                       // ready to switch on
      else c = cw::enable;                                                            // switched on / enabled
      if (operation_enabled(status_)) power_ = Power::enabled;
      break;
    case Power::enabled: c = cw::enable; break;
    case Power::disabling: c = cw::shutdown; break;
  }
  if (power_ == Power::enabled || power_ == Power::manual) {
    // pp hand-over: bit 4 up until the drive acknowledges with 6041h bit 12, then down again.
    if (set_point_pending_) {
      c = static_cast<std::uint16_t>(c | cw::new_set_point | (relative_ ? cw::relative : 0));
      if (status_ & kSetPointAck) set_point_pending_ = false;
    }
  }
  if (power_ != Power::manual) controlword_ = c;
  last_cw_ = c;

  std::int32_t position = tracking_ ? position_ : position_target_;
  if (motion_) {
    const double t = 1e-9 * static_cast<double>(now - motion_start_);
    double x = motion_origin_;
    if (motion_->shape == MotionAction::Shape::ramp) {
      const double distance = motion_->position - motion_origin_;
      const double travelled = std::min(std::abs(distance), motion_->velocity * t);
      x = motion_origin_ + std::copysign(travelled, distance);
      if (travelled >= std::abs(distance)) {
        position_target_ = static_cast<std::int32_t>(std::lround(motion_->position));
        motion_.reset();
      }
    } else {
      const double tt = std::min(t, 1e-9 * static_cast<double>(motion_->duration));
      x = motion_origin_ + motion_->amplitude * (1.0 - std::cos(2.0 * std::numbers::pi * motion_->frequency_hz * tt));
      if (t * 1e9 >= static_cast<double>(motion_->duration)) {
        position_target_ = static_cast<std::int32_t>(std::lround(x));
        motion_.reset();
      }
    }
    position = motion_ ? static_cast<std::int32_t>(std::lround(x)) : position_target_;
    if (motion_) position_target_ = position;
  }
  master::image_put<std::uint16_t>(image, cw_, c);
  master::image_put<std::int8_t>(image, mode_, mode_value_);
  master::image_put<std::int32_t>(image, target_position_, position);
  master::image_put<std::int32_t>(image, target_velocity_, velocity_target_);
  master::image_put<std::int16_t>(image, target_torque_, torque_target_);
}

void AxisControl::inputs(std::span<const std::uint8_t> image) {
  if (!mapped_) return;
  status_ = master::image_get<std::uint16_t>(image, status_at_);
  position_ = master::image_get<std::int32_t>(image, position_at_);
}

}  // namespace vdrive::scenario
