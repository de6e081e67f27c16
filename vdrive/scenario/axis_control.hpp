#pragma once
// The built-in master's program for one CiA 402 drive, as a PLC's motion runtime runs it: in
// Pre-Op it maps the PDOs it needs (RxPDO 1600h: 6040h, 6060h, 607Ah, 60FFh, 6071h; TxPDO 1A00h:
// 6041h, 6061h, 6064h, 606Ch, 6077h, 60F4h, 603Fh), then every cycle writes the controlword, mode
// and set-points the scenario's steps asked for and reads the drive's answer.
//  - enable: fault reset (0->1 edge of bit 7) if faulted, then shutdown, switch on, enable
//    operation, following the statusword (MC_Power + MC_Reset). Once enabled it keeps 000Fh and
//    does not reset a later fault by itself: a scenario enables again to do so.
//  - Until enabled, 607Ah follows 6064h so enabling in csp makes no jump.
//  - pp: a new position is handed over with bit 4, held until 6041h bit 12 acknowledges it.
//  - motion (csp): a ramp or a (1 - cos) sine the master interpolates each cycle.
#include <cstdint>
#include <optional>
#include <span>

#include "common/clock.hpp"
#include "vdrive/scenario/scenario.hpp"

namespace vdrive::master { class Master; struct SlaveProcessData; }

namespace vdrive::scenario {

class AxisControl {
public:
  // Maps the PDOs over CoE. Throws (SdoAbort, MailboxError) if the drive refuses the mapping.
  static void map_pdos(master::Master& master, std::size_t slave);

  // Finds the mapped objects in the image (outputs at `out_base`, inputs at `in_base`); false if
  // the mapping is not the one map_pdos() wrote.
  bool locate(const master::SlaveProcessData& pd, std::uint32_t out_base, std::uint32_t in_base, std::size_t image_size);

  void enable(std::int8_t mode);
  void disable();
  void set_controlword(std::uint16_t value);   // explicit value; ends an enable sequence
  void set_mode(std::int8_t mode);
  void set_target(const TargetAction& t);
  void start_motion(const MotionAction& m, Nanos now);

  void outputs(std::span<std::uint8_t> image, Nanos now);
  void inputs(std::span<const std::uint8_t> image);

  bool mapped() const { return mapped_; }
  std::uint16_t statusword() const { return status_; }
  std::int32_t position() const { return position_; }

private:
  enum class Power : std::uint8_t { manual, enabling, enabled, disabling };

  std::uint32_t cw_ = 0, mode_ = 0, target_position_ = 0, target_velocity_ = 0, target_torque_ = 0;
  std::uint32_t status_at_ = 0, position_at_ = 0;
  bool mapped_ = false;

  Power power_ = Power::manual;
  std::uint16_t controlword_ = 0;
  std::uint16_t last_cw_ = 0;
  std::int8_t mode_value_ = 0;
  std::int32_t position_target_ = 0;
  std::int32_t velocity_target_ = 0;
  std::int16_t torque_target_ = 0;
  bool set_point_pending_ = false;   // pp: bit 4 raised, waiting for 6041h bit 12
  bool relative_ = false;
  bool tracking_ = true;             // 607Ah follows 6064h (not yet enabled, no target set)

  std::optional<MotionAction> motion_;
  Nanos motion_start_ = 0;
  double motion_origin_ = 0.0;

  std::uint16_t status_ = 0;
  std::int32_t position_ = 0;
};

}  // namespace vdrive::scenario
