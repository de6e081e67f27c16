#pragma once
// Homing mode (hm, 6060h = 6): finds the reference point with the method in 6098h and hands it to
// the engine (take_home_found), which presets 6064h = 6062h = 607Ch there (A6B L18429-L18433,
// DS5C1 L3499-L3501, DS1000A-EC L2744-L2746).
//   - start: 6040h bit 4 0->1; a new edge while homing runs is ignored (A6B L17736-L17742, DS5C1
//     L3268-L3270). 6098h, 6099h-01h/02h (limited by 6080h and 2^31-1), 609Ah (acc = dec, 0 -> 1)
//     and 607Ch are latched at the start (A6B L17911-L17982, L18443-L18445).
//   - switch methods 1-14/17-30 and 33/34 follow one table (homing_methods.hpp): search legs at
//     6099h-01h, the final approach across the reference edge and the index search at 6099h-02h.
//     Reversals decelerate with 609Ah, the final stop is a servo lock at the stop point (A6B
//     L17980); the DS1000A-EC stops abruptly at every sensor (L2986-L2988).
//   - 35/37 need no motion and run outside Operation enabled too; bit 12 drops for about 2 ms
//     (A6B L18209-L18212, L19289-L19319).
//   - vendor methods (homing_rules.hpp): DS5C1 -1/-2 hard stop with P9-16..P9-20 and P7-20,
//     DS1000A-EC -1..-4 torque limit (+ index); A6B -1..-4 are "manufacturer use" with no documented
//     sequence: starting one is a homing error.
//   - homing errors (bit 13; A6B L18647-L18734, DS5C1 L3520-L3529): method not supported, start
//     outside Operation enabled (except 35/37), a speed of 0 (33/34 need only the one they use),
//     both limits, a limit in the direction of travel outside the legs that reverse on it, the
//     switch flipping back during a reversal deceleration. While the axis still moves the bits read
//     100, once stopped 101.
//   - halt (bit 8) aborts homing when profile.drive.halt_aborts_homing (decelerating by 605Dh),
//     else pauses it; a cancel between home detection and completion raises the product's alarm
//     (A6B Err27.7, L18526-L18528) through pending_alarm().
// Status (b13, b12, b10): 000 running, 001 interrupted or not started, 010 home found but still
// moving, 011 done, 100 error while moving, 101 error stopped (A6B L18182-L18202).
//
// Frames: the set-point of the step in which home was found is in the frame of that step's sample;
// afterwards the mode assumes the engine re-referenced as documented (new = old - position + 607Ch).
#include <cstdint>
#include <string_view>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/hold_timer.hpp"
#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/modes/homing_methods.hpp"
#include "vdrive/drive/modes/homing_rules.hpp"
#include "vdrive/drive/motion_ramp.hpp"
#include "vdrive/drive/object_ref.hpp"

namespace vdrive::drive {

class HomingMode final : public ModeHandler {
public:
  enum class Phase : std::uint8_t {
    Idle,         // not running: outcome() says how the last run ended
    Seek,         // search leg at 6099h-01h until the reference switch changes
    Brake,        // decelerating before a reversal
    Approach,     // final approach across the reference edge at 6099h-02h
    IndexSearch,  // first index pulse beyond the edge
    Push,         // vendor hard-stop / torque-limit push
    PushIndex,    // DS5C1: P7-20 index pulses back from the hard stop
    FixedMove,    // DS5C1: the P9-19/P9-20 distance
    Settle,       // home found, servo lock until the axis stands
    Pulse,        // 35/37: bit 12 low for about 2 ms
    Stopping,     // halt or error: decelerating
  };
  enum class Outcome : std::uint8_t { NotStarted, Interrupted, Completed, Error };

  explicit HomingMode(const DriveContext& ctx);

  std::int8_t mode() const override { return mode::hm; }
  void activate(const AxisSample& s) override;
  Setpoint step(const AxisSample& s, std::uint16_t controlword) override;
  void idle(const AxisSample& s, std::uint16_t controlword) override;
  std::uint16_t status_bits() const override;
  bool take_home_found(double& position) override;
  std::string_view pending_alarm() override;

  // Engine hooks. Bit 12 is cleared at power-on and Init->PreOp (A6B L18203-L18214, DS5C1
  // L3431-L3436); an absolute-encoder A6B reports it set from power-on (A6B L18222).
  void clear_attained() { attained_ = false; }
  void set_attained() { attained_ = true; }
  bool attained() const { return attained_; }
  // Homing moves the axis (soft limits off, mode switches wait: A6B L10589-L10663).
  bool running() const { return phase_ != Phase::Idle && phase_ != Phase::Pulse; }

  Phase phase() const { return phase_; }
  Outcome outcome() const { return outcome_; }

private:
  enum class Region : std::uint8_t { Unknown, Below, Inside, Above };
  struct Leg {
    Phase phase = Phase::Idle;
    int direction = 0;
    double speed = 0.0;
  };

  void start(const AxisSample& s, bool enabled);
  bool start_error(const AxisSample& s, bool enabled) const;
  void fail(const AxisSample& s);
  void stop(Outcome outcome, double deceleration);
  void found(const AxisSample& s, double reference_point);
  void plan_next();
  void begin_leg(Leg leg, HomingSwitch watch = HomingSwitch::None, bool watch_state = false);
  Region pre_edge_region() const;
  bool reference_active(std::uint32_t inputs) const;
  bool runs_into_limit(const AxisSample& s, int direction) const;
  double halt_deceleration() const;

  Setpoint run(const AxisSample& s, double velocity, double torque_limit = 0.0);
  Setpoint hold() const;
  Setpoint step_seek(const AxisSample& s);
  Setpoint step_brake(const AxisSample& s);
  Setpoint step_approach(const AxisSample& s);
  Setpoint step_index(const AxisSample& s);
  Setpoint step_push(const AxisSample& s);
  Setpoint step_push_index(const AxisSample& s);
  Setpoint step_fixed_move(const AxisSample& s);
  void after_push(const AxisSample& s, double stop_position);
  void finish_pulse(const AxisSample& s);

  const DriveContext& ctx_;
  const profile::HomingSpec& rules_;  // the product's homing section: vendor methods and rules
  ObjectRef<std::int8_t> method_;
  ObjectRef<std::uint32_t> speed_switch_, speed_zero_, acceleration_, max_motor_speed_, quick_stop_dec_;
  ObjectRef<std::int32_t> home_offset_;
  ObjectRef<std::int16_t> halt_option_;
  ObjectRef<std::uint16_t> positive_torque_, negative_torque_;
  // DS5C1 hard stop (P-parameter index = 2000h | group << 8 | number, digest 7.2 / L5834-L5844).
  ObjectRef<std::int32_t> stop_speed_rpm_, stop_torque_pct_, stop_time_ms_, fixed_low_, fixed_high_, z_count_;
  // DS1000A-EC torque-limit detection time 2142h (L4168-L4170).
  ObjectRef<std::uint16_t> torque_detect_ms_;

  // The run.
  const HomingMethodSpec* spec_ = nullptr;
  const HardStopMethod* hard_ = nullptr;
  Phase phase_ = Phase::Idle;
  Outcome outcome_ = Outcome::NotStarted;
  Leg leg_{}, next_{};
  Region where_ = Region::Unknown;
  HomingSwitch watch_ = HomingSwitch::None;  // must keep `watch_state_` while braking
  bool watch_state_ = false;
  HomingSwitch exempt_limit_ = HomingSwitch::None;  // the limit a brake reverses on
  double v_switch_ = 0.0, v_zero_ = 0.0, acc_ = 1.0;
  double reference_value_ = 0.0;  // what 6064h reads at the reference point
  double edge_position_ = 0.0;
  double push_limit_ = 0.0;
  double fixed_target_ = 0.0;
  int index_left_ = 0;
  HoldTimer push_timer_;
  Nanos pulse_end_ = 0;
  double stop_decel_ = 0.0;
  Outcome stop_outcome_ = Outcome::Interrupted;
  bool error_ = false;
  bool attained_ = false;
  bool prev_start_ = true;
  MotionState cmd_{};

  double frame_shift_ = 0.0;  // applied to cmd_ at the next step, after the engine re-referenced
  bool home_pending_ = false;
  double home_position_ = 0.0;
  std::string_view alarm_;
};

}  // namespace vdrive::drive
