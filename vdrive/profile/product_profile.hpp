#pragma once
// A product, as data: everything that makes a slave one product rather than a generic ESC; no
// behaviour is chosen by comparing its id. Loaded from profiles/<id>/profile.yaml (see
// profile_loader.hpp); the object dictionary comes from profiles/<id>/objects.yaml, alarms and
// motors from alarms.yaml and motors.yaml. Each section has its own header; this one puts them
// together.
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/profile/alarm_motor_spec.hpp"
#include "vdrive/profile/drive_spec.hpp"
#include "vdrive/profile/esc_spec.hpp"
#include "vdrive/profile/motion_spec.hpp"
#include "vdrive/profile/pdo_spec.hpp"
#include "vdrive/profile/sync_spec.hpp"

namespace vdrive::profile {

struct ProductProfile {
  std::string id;                    // the folder name under profiles/
  std::string title;                 // human name, e.g. "Panasonic MINAS-A6B"
  Identity identity;
  EscResources esc;
  Mailbox mailbox;
  MailboxSmRules mailbox_rules;
  std::vector<SyncManagerSpec> sync_managers;  // SII SyncManager category, in SM order
  // SII FMMU category (ecat::sii::fmmu_usage values), when the device lists fewer FMMUs than its
  // ESC has (an input terminal: Inputs only). Empty: Outputs, Inputs, MailboxState for
  // esc.fmmu_count.
  std::vector<std::uint8_t> fmmu_usage;
  bool has_bootstrap = false;                  // Boot state supported
  // Explicit Device ID (ETG.1000.6): AL control bit5 puts the device ID into AL status code 0x0134
  // and sets AL status bit5. A6B and DS1000A-EC support it, DS5C1 does not.
  bool explicit_device_id = false;
  AlStatusCodes al_codes;
  SiiCheck sii_check;                          // profile.yaml `sii_check` (absent: no check)
  // SII General category: CoE details (bit0 SDO, 1 SDO info, 2 PDO assign, 3 PDO config,
  // 4 startup upload, 5 complete access), FoE details, ports.
  std::uint8_t coe_details = 0x0F;
  std::uint8_t foe_details = 0;
  // FoE firmware download: true = only a file named ECATFW__... holding a valid vdrive image
  // (firmware_image.hpp) is taken, with password 0 (the ETG SSC's checks, for scenarios that test
  // a master's error handling); false = any file name, password and content in Boot (profile.yaml
  // `foe_strict_firmware_check`, default false: the manuals give neither, docs/foe.md).
  bool foe_strict_firmware_check = false;
  // SDO abort for a complete-access request when coe_details bit5 is clear (A6B 06010000h: its abort
  // table has no 06010004h; ETG.1000.6 06010004h otherwise).
  std::uint32_t complete_access_abort = 0x06010004;
  // Default PDO mappings (factory values), in object order. Empty when the manual gives none.
  std::vector<PdoSpec> rx_pdos;
  std::vector<PdoSpec> tx_pdos;
  // The rest of the product (profile.yaml keys sync, pdo_rules, modes, homing,
  // touch_probe; alarms.yaml; motors.yaml).
  SyncSpec sync;
  PdoRules pdo_rules;
  ModesSpec modes;
  HomingSpec homing;
  TouchProbeSpec touch_probe;
  std::vector<AlarmSpec> alarms;                      // profiles/<id>/alarms.yaml, in manual order
  std::vector<MotorSpec> motors;                      // profiles/<id>/motors.yaml (at least one entry)
  DriveSpec drive;                                    // profile.yaml `drive`

  // Whether the device has a mailbox at all (an SM for it); simple I/O devices have none.
  bool has_mailbox() const {
    for (const SyncManagerSpec& sm : sync_managers)
      if (sm.kind == SyncManagerSpec::Kind::MailboxOut) return true;
    return false;
  }
  // The SyncManager that carries outputs (kind Outputs) or inputs, or `otherwise` when none does.
  int process_data_sm(SyncManagerSpec::Kind kind, int otherwise) const {
    for (std::size_t i = 0; i < sync_managers.size(); ++i)
      if (sync_managers[i].kind == kind) return static_cast<int>(i);
    return otherwise;
  }

  // The alarm with vendor code `code` ("80.4", "E-804", "FF80h"), or nullptr.
  const AlarmSpec* find_alarm(std::string_view code) const {
    for (const AlarmSpec& a : alarms)
      if (a.code == code) return &a;
    return nullptr;
  }
  // The first alarm (manual order) that shows `error_code` in 603Fh, or nullptr.
  const AlarmSpec* alarm_with_error_code(std::uint16_t error_code) const {
    for (const AlarmSpec& a : alarms)
      if (a.error_code == error_code) return &a;
    return nullptr;
  }
};

}  // namespace vdrive::profile
