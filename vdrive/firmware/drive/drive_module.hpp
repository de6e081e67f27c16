#pragma once
// The CiA 402 drive as a firmware module: owns the plant the drive moves (FirmwareOptions::plant,
// else drive::default_plant(profile); axis 0 is this drive's motor) and the DriveEngine, and runs
// the engine's control steps on the firmware's clock: at their own period through tick(), and up to
// the instant of each process-data exchange (outputs taken over, inputs about to be gathered), so
// the TxPDO carries the drive's state at that moment. Emergencies go out through the mailbox.
// EtherCAT errors become the product's alarms: an AL status code the firmware reports (watchdog
// 001Bh, lost SYNC0 002Ch, a refused transition ...) raises the alarm of alarms.yaml with that
// al_status_code (A6B Err80.x/81.x/85.x, DS5C1 E-80x/E-81x/E-85x), whose clearing then waits for
// the master's AL acknowledge; leaving Op while enabled without such an error is the product's
// "ESM change" alarm (A6B Err88.2, DS5C1 E-882, DS1000A-EC FF80h).
// Batched control steps (set_step_batch, real time only): the loop need not wake for each step;
// a step waits up to that long and runs, with its own instant, in a batch at the next call that
// catches the drive up (an interrupt, an exchange, a loop round: Network::catch_up, step_once).
// Installed for products that list drive modes (6502h != 0).
#include <memory>

#include "ethercat/emergency.hpp"
#include "plant/plant.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/pdo/pdo_mapping.hpp"

namespace vdrive::firmware::drive_module {

class DriveModule final : public FirmwareModule {
public:
  // `emergency` posts one emergency message (the mailbox module's queue).
  DriveModule(FirmwareContext& context, const plant::PlantDescription& plant,
              std::function<void(const ecat::coe::Emergency&)> emergency);
  ~DriveModule() override;

  void power_on(Nanos now) override;
  void entered(ecat::AlState from, ecat::AlState to, Nanos now) override;
  void tick(Nanos now) override;
  Nanos next_deadline() const override;

  // How long a due control step may wait for a catch-up before the loop must wake for it; 0 (the
  // default): not at all, each step is a deadline of its own.
  void set_step_batch(Nanos wait) { step_batch_ = wait; }
  // What tick() runs, whether or not it is due, for one control step at most: the alarm for a new
  // AL error and the next step if it is due by `now`; true if one ran. Network::catch_up interleaves
  // the drives with it, so an observer (the mailbox, a sample, a fault) sees them as of now.
  bool step_once(Nanos now);

  // Process-data hooks (ProcessDataModule::set_application).
  void after_outputs(Nanos now);
  void before_inputs(Nanos now);
  // The RxPDO mapping that just became effective (ProcessDataModule::on_outputs_mapped).
  void outputs_mapped(const pdo::ResolvedMapping& rx);

  vdrive::drive::DriveEngine& engine() { return *engine_; }
  plant::Plant& plant() { return plant_; }

private:
  vdrive::drive::BusState bus() const;
  void catch_up(Nanos now);  // the control steps due by now, if any
  // Raises the alarm for a new AL status code; true if the product has one for it.
  bool raise_al_error(Nanos now);

  FirmwareContext& context_;
  plant::Plant plant_;
  std::unique_ptr<vdrive::drive::DriveEngine> engine_;
  vdrive::drive::MappedOutputs mapped_;  // scratch for outputs_mapped(): no allocation there
  std::uint16_t al_error_seen_ = 0;   // the AL status code already turned into an alarm
  Nanos step_batch_ = 0;
};

}  // namespace vdrive::firmware::drive_module
