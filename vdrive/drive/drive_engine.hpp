#pragma once
// The CiA 402 drive of one slave: every control period (profile.drive.control_period_ns) it samples
// its plant axis, runs the power drive system (PdsMachine), the active mode (ModeSelector + one
// ModeHandler per mode of 6502h) or the stop that runs, the motion limits, the control loop, the
// vendor alarms, the digital I/O and the touch probe, commands the motor and publishes the actual
// values (6041h, 6061h, 6062h-6064h, 606Bh, 606Ch, 6074h, 6077h, 60F4h, 603Fh).
//
// The firmware calls it at four moments: power_on(), esm_changed() (the EtherCAT state machine
// moved), outputs_taken() (new RxPDO values reached the dictionary) and advance_to(now) (run the
// control steps that are due; also right before the TxPDO objects are gathered). Positions are
// referenced at power-on (absolute encoders: from the encoder; incremental: 0) and by homing.
// Nothing allocates after construction.
#include <array>
#include <cstdint>
#include <memory>
#include <string_view>

#include "common/clock.hpp"
#include "ethercat/al_state.hpp"
#include "plant/plant.hpp"
#include "vdrive/drive/alarms/alarm_manager.hpp"
#include "vdrive/drive/alarms/alarm_monitors.hpp"
#include "vdrive/drive/axis_objects.hpp"
#include "vdrive/drive/control/control_loop.hpp"
#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/injected_fault.hpp"
#include "vdrive/drive/io/digital_io.hpp"
#include "vdrive/drive/io/touch_probe.hpp"
#include "vdrive/drive/mapped_outputs.hpp"
#include "vdrive/drive/mode_handler.hpp"
#include "vdrive/drive/mode_selector.hpp"
#include "vdrive/drive/motion_limits.hpp"
#include "vdrive/drive/pds/pds_machine.hpp"
#include "vdrive/drive/pds/stop_sequence.hpp"
#include "vdrive/drive/unit_scaling.hpp"
#include "vdrive/drive/vendor_monitors.hpp"

namespace vdrive::drive {

class HomingMode;

// What the drive knows of the EtherCAT side when it steps.
struct BusState {
  bool esm_init = true;          // ESM in Init (PDS transitions 7/10)
  bool remote = false;           // ESM >= PreOp: 6041h bit 9 (A6B L10078, DS5C1 L6032)
  bool al_error_pending = false; // AL status error flag not yet acknowledged (alarm clearing)
  std::uint64_t system_time_ns = 0;  // DC system time (touch probe time stamps)
};

class DriveEngine {
public:
  // `plant` and `axis` are the motor this drive commands (both outlive the engine); `axis_spec` is
  // that axis's description (motor data, encoder).
  DriveEngine(const profile::ProductProfile& profile, od::ObjectStore& objects, plant::Plant& plant,
              std::size_t axis, const plant::AxisSpec& axis_spec, AlarmManager::EmergencySink emergencies);
  ~DriveEngine();
  DriveEngine(const DriveEngine&) = delete;
  DriveEngine& operator=(const DriveEngine&) = delete;

  // Control power on at `now` (the store was reset to defaults and the stored parameters loaded).
  void power_on(Nanos now);
  // The ESM moved from `from` to `to`. Leaving Op while the power stage is on is the product's
  // "ESM change while enabled" alarm (A6B Err88.2, DS5C1 E-882, DS1000A-EC FF80h), unless the
  // move was an EtherCAT error that already raised its own alarm (`by_error`).
  void esm_changed(ecat::AlState from, ecat::AlState to, Nanos now, bool by_error = false);
  // New outputs reached the RxPDO objects (a bus cycle): cyclic modes take their set-point.
  void outputs_taken(Nanos now);
  // A PDO mapping became effective (PreOp->SafeOp): the objects its RxPDO carries every cycle.
  void outputs_mapped(const MappedOutputs& outputs);
  // Runs every control step due up to `now`; `bus` as it is at `now` (each step gets the DC time
  // of its own instant).
  void advance_to(Nanos now, const BusState& bus);
  // Runs the next control step if it is due by `now` (one at most, so a caller can interleave the
  // drives of a line step by step); true if it ran one.
  bool advance_one(Nanos now, const BusState& bus);
  Nanos next_step() const { return next_step_; }
  Nanos control_period() const { return period_; }

  // Observers and fault injection (tests, scenarios, telemetry).
  PdsState state() const { return pds_.state(); }
  std::int8_t mode() const { return selector_.active(); }
  const AxisSample& sample() const { return sample_; }
  AlarmManager& alarms() { return alarms_; }
  const UnitScaling& units() const { return units_; }
  plant::Plant& plant() { return plant_; }
  std::size_t axis() const { return axis_; }
  // Raise a vendor alarm by its code ("24.0", "E-100", "FF02h"); false if the product has none.
  bool raise_alarm(std::string_view code, Nanos now);
  // Raise the alarm whose AL status code is `al_status_code`; false if the product has none.
  bool raise_al_error(std::uint16_t al_status_code, Nanos now);
  // Main (power-stage) supply present (PDS transition 3 needs it).
  void set_main_power(bool on) { main_power_ = on; }
  // An injected fault's cause appears (active) or goes away (injected_fault.hpp). While active the
  // product's alarm for it (profile.drive.alarms; none: nothing) is raised and its clearing is
  // refused; main_power_off / under_voltage also take the main power away (6041h bit 4, the PDS's
  // main-power input), and where the product detects supply loss only with the servo on
  // (supply_alarms_only_when_enabled) their alarm waits for the power stage to be on.
  void set_injected_fault(InjectedFault fault, bool active, Nanos now);
  bool injected_fault(InjectedFault fault) const { return injected_[fault_index(fault)]; }
  // The STO / TO input (true = torque off requested).
  void set_torque_off_input(bool on) { torque_off_input_ = on; }

private:
  void step(Nanos t, const BusState& bus);
  AxisSample measure(Nanos t, const plant::AxisFeedback& fb) const;
  void command(const Setpoint& sp, const plant::AxisFeedback& fb, double dt);
  void latch_units();
  ModeHandler* handler_for(std::int8_t mode) const;
  void raise_cause(std::string_view code, Nanos t);
  void raise_injected(InjectedFault fault, Nanos t);
  bool main_power_present() const;
  void rereference(double found_position);
  void publish(const AxisSample& s, const plant::AxisFeedback& fb);

  const profile::ProductProfile& profile_;
  od::ObjectStore& objects_;
  plant::Plant& plant_;
  std::size_t axis_;
  UnitScaling units_;
  DriveContext ctx_;
  AxisObjects obj_;
  VendorMonitors vendor_monitors_;
  PdsMachine pds_;
  StopSequence stop_;
  ModeSelector selector_;
  MotionLimits limits_;
  AlarmManager alarms_;
  AlarmMonitors monitors_;
  DigitalIo io_;
  TouchProbe probe_;
  plant::AxisSpec axis_spec_;
  std::unique_ptr<ControlLoop> loop_;
  std::array<std::unique_ptr<ModeHandler>, 11> handlers_{};  // by 6060h value 1..10
  HomingMode* homing_ = nullptr;
  ModeHandler* active_ = nullptr;

  Nanos period_ = 125'000;
  Nanos next_step_ = 0;
  Nanos epoch_ = 0;                // time of power-on: the plant's time 0
  AxisSample sample_{};
  Setpoint last_{};
  double demand_position_ = 0.0;    // 6062h (user), continued through velocity and torque set-points
  double demand_velocity_ = 0.0;    // 606Bh (user/s)
  double zero_rad_ = 0.0;          // motor angle where the unreferenced user position is 0
  double offset_user_ = 0.0;       // user position = to_user(angle - zero_rad_) + offset_user_
  std::uint32_t previous_inputs_ = 0;
  bool powered_ = false;           // the power stage was on in the previous step
  bool was_enabled_ = false;       // Operation enabled and motion allowed in the previous step
  bool homed_ = false;
  bool main_power_ = true;
  bool torque_off_input_ = false;
  std::array<bool, kInjectedFaultCount> injected_{};
  std::array<const profile::AlarmSpec*, kInjectedFaultCount> injected_alarms_{};   // nullptr: the product has none
  bool cycle_pending_ = false;
  Nanos cycle_time_ = 0;
  // Set by an SDO write of the product's drive-clear value (alarm_rules.drive_clear, DS5C1 4000h = 1),
  // taken by the next control step. Shared with the store's write hook, which may outlive the engine.
  std::shared_ptr<bool> drive_clear_request_ = std::make_shared<bool>(false);
};

}  // namespace vdrive::drive
