#pragma once
// The firmware of one slave: what the drive's microcontroller runs. It talks to its ESC only
// through the PDI (pdi_read/pdi_write/pdi_irq), like the real thing.
//
// The EtherCAT state machine (AL control -> AL status / status code) with the product's mailbox
// SyncManager checks (docs/state-machine.md), and the modules it runs: mailbox (CoE, FoE), process
// data, synchronisation and, for a product with drive modes, the CiA 402 drive.
#include <cstdint>
#include <memory>
#include <optional>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "plant/plant_description.hpp"
#include "vdrive/profile/product_profile.hpp"
#include "vdrive/firmware/sdo_abort_record.hpp"

namespace vdrive::drive { class DriveEngine; }
namespace vdrive::plant { class Plant; }
namespace vdrive::firmware::mailbox { class MailboxModule; }
namespace vdrive::od { class Dictionary; class ObjectStore; }

namespace vdrive::firmware {

struct FirmwareOptions {
  // The machine the drive moves (axis 0 is its motor); empty = drive::default_plant(profile).
  std::optional<plant::PlantDescription> plant;
  // Where the profile was loaded from: its objects.yaml is looked for there first (a product that
  // exists only as files has no built-in dictionary). Empty: the built-in dictionaries.
  std::string profile_dir;
  // The object dictionary, when it does not come from the profile's objects.yaml (a device imported
  // from its ESI file). Empty: od::shared_dictionary(profile, profile_dir).
  std::shared_ptr<const od::Dictionary> dictionary;
};

class SlaveFirmware {
public:
  SlaveFirmware(const profile::ProductProfile& profile, esc::Esc& esc, const FirmwareOptions& options = {});
  ~SlaveFirmware();

  // Power-on: initialise AL status (Init), load what the firmware loads at boot.
  void power_on(Nanos now);
  // Service the PDI interrupt (call after each frame when esc.pdi_irq() != 0, and on SYNC).
  void on_irq(Nanos now);
  // Periodic work (timeouts, cyclic tasks); call at next_deadline() at the latest.
  void tick(Nanos now);
  Nanos next_deadline() const;

  // Batched control steps (real time): the drive's steps may wait up to `wait` for the next
  // step_once() instead of each being a deadline (Network::catch_up runs them, before every
  // interrupt, so the mailbox, the process data and the AL state machine see the drive as of that
  // instant). 0, the default: each step is due at its own instant.
  void set_control_step_batch(Nanos wait);
  // Runs the drive's next control step if it is due by `now`; true if one ran.
  bool step_once(Nanos now);
  // The instant of the drive's next control step, whether or not the loop must wake for it;
  // INT64_MAX without a drive.
  Nanos next_control_step() const;

  // The drive's ID switches as Explicit Device ID (AL Control bit5) reports them in AL status
  // code: A6B rotary switch (low byte) + object 3740h (high byte), L5802-L5924; DS1000A-EC rotary
  // ID switch, L789-L795. Until set, the firmware reports the station alias register 0x0012.
  void set_device_id_switch(std::uint16_t id);

  // The CiA 402 drive (products with drive modes), nullptr for other devices. For observers,
  // tests and fault injection; single-threaded like the rest of the firmware.
  drive::DriveEngine* drive();
  // The plant that drive moves (nullptr without a drive), and the mailbox module; for fault
  // injection and observers, on the firmware's thread.
  plant::Plant* plant();
  mailbox::MailboxModule& mailbox();
  // This slave's object values (scenario expectations and traces read them as the drive has them).
  od::ObjectStore& objects();
  // The SDO aborts this slave has answered (count and the last), for observers.
  const SdoAbortRecord& sdo_aborts() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdrive::firmware
