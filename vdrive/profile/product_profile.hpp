#pragma once
// A product, as data: everything that makes a slave one product rather than a generic ESC; no
// behaviour is chosen by comparing its id. Loaded from profiles/<id>/profile.yaml (see profile_loader.hpp). The object
// dictionary comes from profiles/<id>/objects.yaml; alarms and motors from alarms.yaml and motors.yaml.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ethercat/al_status_code.hpp"
#include "ethercat/sii.hpp"

#include "vdrive/profile/product_rules.hpp"

namespace vdrive::profile {

struct Identity {
  std::uint32_t vendor_id = 0;
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
  std::uint32_t serial = 0;
  std::uint32_t device_type = 0;      // 1000h
  std::string device_name;            // 1008h and SII device name string
  std::string hardware_version;       // 1009h
  std::string software_version;       // 100Ah
  std::string vendor_name;            // SII/ESI vendor string
  std::string order_code;             // SII order string (ESI Type)
  std::string group;                  // SII group string (ESI group type)
};

// One SyncManager as the product's SII/ESI declares it (default start, length, control, enable).
struct SyncManagerSpec {
  std::uint16_t start = 0;
  std::uint16_t length = 0;
  std::uint8_t control = 0;
  bool enable = true;
  enum class Kind : std::uint8_t { MailboxOut = 1, MailboxIn = 2, Outputs = 3, Inputs = 4 } kind{};
};

struct Mailbox {
  std::uint16_t rx_offset = 0x1000, rx_size = 0x80;   // master -> slave (SM0)
  std::uint16_t tx_offset = 0x1080, tx_size = 0x80;   // slave -> master (SM1)
  std::optional<std::uint16_t> boot_rx_offset, boot_rx_size, boot_tx_offset, boot_tx_size;
  std::uint16_t protocols = ecat::sii::mailbox_protocol::kCoE;  // SII word 0x1C
};

// Rules the firmware checks for the mailbox SyncManagers at Init->Pre-Op (and Init->Boot).
struct MailboxSmRules {
  std::uint16_t sm0_min_length = 32, sm0_max_length = 0xFFFF;
  std::uint16_t sm1_min_length = 32, sm1_max_length = 0xFFFF;
  std::uint16_t sm0_start_min = 0x1000, sm0_start_max = 0xFFFF;
  std::uint16_t sm1_start_min = 0x1000, sm1_start_max = 0xFFFF;
  std::uint8_t sm0_control_mask = 0x0F, sm0_control_value = 0x06;  // mailbox, write
  std::uint8_t sm1_control_mask = 0x0F, sm1_control_value = 0x02;  // mailbox, read
  bool require_even_start = true;
};

struct EscResources {
  std::uint8_t type = 0x04, revision = 0x02;
  std::uint16_t build = 0x0044;
  std::uint8_t fmmu_count = 3, sm_count = 4, ram_kib = 8, port_descriptor = 0x0F;
  std::uint16_t features = 0x018C;
  std::uint16_t eeprom_bytes = 2048;                 // SII word 0x3E: (kbit) - 1
  std::uint16_t pdi_control = 0x0C05, pdi_config = 0x6603, sync_pulse_length = 0x0064;
  std::uint16_t extended_pdi_config = 0, station_alias = 0;
};

// AL status codes the product reports, by situation: ETG.1000.6's code unless profile.yaml names the
// product's own. 0 = the product does not report one.
struct AlStatusCodes {
  std::uint16_t invalid_transition = ecat::al_status_code::kInvalidStateChange;
  std::uint16_t unknown_state = ecat::al_status_code::kUnknownState;
  std::uint16_t bootstrap_not_supported = ecat::al_status_code::kBootstrapNotSupported;
  std::uint16_t invalid_mailbox_config = ecat::al_status_code::kInvalidMailboxConfig;
  std::uint16_t invalid_boot_mailbox_config = ecat::al_status_code::kInvalidBootMailboxConfig;
  // Codes checked at PreOp->SafeOp and in SafeOp/Op (ETG.1000.6 names; products pick their own).
  std::uint16_t sync_watchdog = ecat::al_status_code::kSyncManagerWatchdog;  // process-data (SM2) watchdog expired
  std::uint16_t invalid_output_config = ecat::al_status_code::kInvalidOutputConfig;  // SM2
  std::uint16_t invalid_input_config = ecat::al_status_code::kInvalidInputConfig;  // SM3
  std::uint16_t invalid_watchdog_config = ecat::al_status_code::kInvalidWatchdogConfig;
  std::uint16_t invalid_input_mapping = ecat::al_status_code::kInvalidInputMapping;  // TxPDO
  std::uint16_t invalid_output_mapping = ecat::al_status_code::kInvalidOutputMapping;  // RxPDO
  std::uint16_t sync_mode_not_supported = ecat::al_status_code::kSyncModeNotSupported;
  std::uint16_t sync_error = ecat::al_status_code::kFatalSyncError;  // SYNC0/IRQ missed
  std::uint16_t no_sync_error = ecat::al_status_code::kNoSyncError;  // sync not locked in time
  std::uint16_t invalid_dc_sync_config = ecat::al_status_code::kInvalidDcSyncConfig;
  std::uint16_t pll_error = ecat::al_status_code::kPllError;
  std::uint16_t invalid_sync_cycle_time = ecat::al_status_code::kDcInvalidSyncCycleTime;
  std::uint16_t eeprom_error = ecat::al_status_code::kEepromError;  // SII EEPROM/identity mismatch
};

// One entry of a default PDO mapping (SII TxPDO/RxPDO categories, 16xxh/1Axxh).
struct PdoEntrySpec {
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint8_t bit_length = 0;
  std::uint8_t data_type = 0;          // CoE data type code: 0x05 U8, 0x06 U16, 0x07 U32, 0x03 I16...
  std::string name;
};

// A PDO of the default mapping: its mapping object and the SyncManager it is assigned to.
struct PdoSpec {
  std::uint16_t index = 0;             // 0x1600.. (RxPDO) or 0x1A00.. (TxPDO)
  std::string name;
  std::uint8_t sync_manager = 0;       // 2 = outputs, 3 = inputs; 0xFF = not assigned by default
  bool fixed = false;                  // mapping cannot be changed
  std::vector<PdoEntrySpec> entries;
};

// --- Synchronisation (1C32h/1C33h, ETG.1020 / ETG.6010) -------------------------------------------

// Sync types as 1C32h-01h/1C33h-01h hold them (ETG.1020): the product's accepted values are listed
// per object in SyncObjectSpec::accepted_sync_types.
enum class SyncType : std::uint16_t {
  FreeRun = 0x00,         // local timer, no synchronisation
  Sm2Event = 0x01,        // 1C32h: synchronous with SM2 event
  DcSync0 = 0x02,         // synchronous with SYNC0
  DcSync1 = 0x03,         // synchronous with SYNC1
  Sm2EventInputs = 0x22,  // 1C33h: inputs latched synchronous with the SM2 event
};

// The values one of 1C32h (outputs, SM2) or 1C33h (inputs, SM3) holds after power-up and what the
// product accepts there. Times in ns. Where the manual says "not supported" the value is 0 (the
// subindex reads 0); which subindexes exist is the object dictionary's business (objects.yaml).
struct SyncObjectSpec {
  std::uint16_t default_sync_type = 0;                // 01h after power-up
  std::vector<std::uint16_t> accepted_sync_types;     // 01h values a write / PS check accepts
  std::uint32_t default_cycle_time_ns = 0;            // 02h after power-up
  bool cycle_time_writable = true;                    // 02h rw (else ro, copied from 1C32h/09A0h)
  std::uint32_t default_shift_time_ns = 0;            // 03h after power-up
  bool shift_time_writable = false;                   // 03h rw
  std::uint16_t supported_sync_types = 0;             // 04h (bit0 free run, bit1 SM, bits4-2 DC, bits6-5 shift)
  std::uint32_t min_cycle_time_ns = 0;                // 05h
  std::uint32_t calc_and_copy_time_ns = 0;            // 06h
  std::uint32_t delay_time_ns = 0;                    // 09h
  bool error_counters = false;                        // 0Bh-0Eh are real counters (else read 0); SyncSpec says which counts what
};

// Shift-time rule for 1C33h-03h (input latch after SYNC0/SM2) or 1C32h-03h. max_ns = 0: only 0 is
// accepted (the product has no shift).
struct ShiftTimeRule {
  std::uint32_t step_ns = 0;                          // value must be a multiple of this (0 = any)
  std::uint32_t max_ns = 0;                           // largest accepted value
  bool below_cycle_time = true;                       // must be < 1C32h-02h
  std::vector<std::uint32_t> cycle_times_ns;          // cycles at which a shift is accepted (empty = all)
};

// Process-data (SM2) watchdog rule checked at PreOp->SafeOp when the watchdog is enabled
// (SM2 control bit 6): the timeout, (0400h + 2) * 40 ns * 0420h, must be at least
// min_cycles * cycle time in SM2/DC mode, and at least min_free_run_ns in free run.
struct WatchdogRule {
  std::uint8_t min_cycles = 0;                        // e.g. A6B Err81.4: 2 x cycle (0 = no check)
  std::uint32_t min_free_run_ns = 0;                  // e.g. A6B Err81.4: 2 ms in free run
};

// A drive mode that needs a longer cycle than the product's minimum (e.g. A6B pp/pv/tq >= 250 us).
struct ModeCycleLimit {
  std::int8_t mode = 0;                               // 6060h value
  std::uint32_t min_cycle_ns = 0;
};

struct SyncSpec {
  bool free_run = false;                              // sync modes the product runs in
  bool sm2_event = false;
  bool dc_sync0 = false;
  bool dc_sync1 = false;
  // Cycle times accepted in SM2/DC (1C32h-02h, 09A0h), ascending. When `cycle_step_ns` != 0 the
  // list is empty and any multiple of the step in [cycle_min_ns, cycle_max_ns] is accepted.
  std::vector<std::uint32_t> cycle_times_ns;
  std::uint32_t cycle_step_ns = 0;
  std::uint32_t cycle_min_ns = 0, cycle_max_ns = 0;   // always set: the accepted range
  std::uint32_t free_run_min_interval_ns = 0;         // fastest PDO rate the product takes in free run (0 = not stated)
  bool cycle_must_equal_sync0 = true;                 // DC: 09A0h must equal 1C32h-02h
  std::vector<std::uint8_t> accepted_dc_activation;   // 0981h values accepted at PS (e.g. 0x00, 0x03)
  std::vector<ModeCycleLimit> mode_min_cycle;         // per-mode cycle minimums
  SyncObjectSpec sm2;                                 // 1C32h
  SyncObjectSpec sm3;                                 // 1C33h
  ShiftTimeRule input_shift;                          // 1C33h-03h
  ShiftTimeRule output_shift;                         // 1C32h-03h
  WatchdogRule watchdog;
  std::uint32_t pll_lock_timeout_ns = 0;              // sync must lock within this after PS (0 = not stated)
  std::uint8_t missed_sync_threshold = 0;             // consecutive SYNC0/IRQ misses before a sync error (0 = never)
  // Where the product keeps that threshold instead: bits 3-0 of this object's subindex 0 (A6B 3742h);
  // 0 = missed_sync_threshold applies.
  std::uint16_t missed_sync_threshold_object = 0;
  // Object (subindex 0) counting SYNC0/IRQ misses (A6B 4F78h); 0 = none.
  std::uint16_t sync_error_count_object = 0;
  // At PreOp->SafeOp 1C32h-01h/1C33h-01h are rewritten from 0981h: DC on -> DC SYNC0; DC off -> a
  // DC SYNC0 setting becomes free run (A6B L7750-L7780).
  bool sync_types_follow_dc_activation = false;
  // The 1C33h-01h value for "inputs synchronous with the SM2 event": 22h (ETG.1020), 01h on the DS5C1.
  std::uint16_t input_sm2_sync_type = 0x22;
  // 1C32h/1C33h subindexes counting missed SM2/SYNC0 events and too-short cycles (0 = not counted).
  std::uint8_t sm_event_missed_subindex = 0;
  std::uint8_t cycle_too_small_subindex = 0;
  bool sync_error_flag = false;                       // 1C32h/1C33h-20h is set on lost sync

  // True when `ns` is a cycle time the product accepts in SM2/DC mode (1C32h-02h / 09A0h).
  bool accepts_cycle(std::uint32_t ns) const {
    if (cycle_step_ns != 0) return ns >= cycle_min_ns && ns <= cycle_max_ns && ns % cycle_step_ns == 0;
    for (const std::uint32_t c : cycle_times_ns)
      if (c == ns) return true;
    return false;
  }
  // The shortest cycle `mode` (6060h) runs at: its mode_min_cycle entry, else cycle_min_ns.
  std::uint32_t min_cycle_for_mode(std::int8_t mode) const {
    for (const ModeCycleLimit& l : mode_min_cycle)
      if (l.mode == mode) return l.min_cycle_ns;
    return cycle_min_ns;
  }
};

// --- PDO mapping rules ---------------------------------------------------------------------------

// One mapping object (16xxh/1Axxh) the product has, default mapping or not.
struct PdoObjectRule {
  std::uint16_t index = 0;
  bool fixed = false;                                 // contents cannot be changed (1600h.. writes refused)
  std::uint8_t max_entries = 0;                       // subindexes 01h..max_entries exist
};

// A set of ESM states: the bit is the AL state code for Init (1), PreOp (2), SafeOp (4), Op (8), so
// `set & al_state` tests those four; Boot (AL code 3) is 0x10.
using EsmStateSet = std::uint8_t;
inline constexpr EsmStateSet kStateInit = 0x01, kStatePreOp = 0x02, kStateSafeOp = 0x04, kStateOp = 0x08,
                             kStateBoot = 0x10;

struct PdoRules {
  std::vector<PdoObjectRule> rx_objects;              // 1600h.. in index order
  std::vector<PdoObjectRule> tx_objects;              // 1A00h.. in index order
  std::uint8_t max_rx_assigned = 0;                   // 1C12h-00h maximum
  std::uint8_t max_tx_assigned = 0;                   // 1C13h-00h maximum
  std::uint16_t max_rx_bytes = 0;                     // total RxPDO size limit (bytes, all assigned PDOs)
  std::uint16_t max_tx_bytes = 0;                     // total TxPDO size limit
  bool assign_writable = true;                        // 1C12h/1C13h can be written at all
  bool mapping_writable = true;                       // free mapping (16xxh/1Axxh not all fixed)
  EsmStateSet writable_states = kStatePreOp;          // states in which 1C1xh/16xxh/1Axxh may change
  bool sub0_must_be_zero = true;                      // subindexes >= 1 writable only while sub 0 = 0
  std::uint32_t wrong_state_abort = 0x06010003;       // SDO abort for a write outside writable_states
  bool checked_at_safeop = true;                      // size/mappability checked at PreOp->SafeOp (not on SDO write)
  bool byte_aligned_total = false;                    // total size must be whole bytes (padding rule)
};

// --- Drive modes, homing, touch probe ------------------------------------------------------------

struct ModesSpec {
  std::uint32_t supported_drive_modes = 0;            // 6502h value
  std::vector<std::int8_t> modes;                     // 6060h values accepted (besides 0 = no mode)
  std::int8_t default_mode = 0;                       // 6060h after power-up
};

struct HomingSpec {
  std::vector<std::int8_t> methods;                   // 6098h values the drive accepts
  std::vector<std::int8_t> listed;                    // 60E3h subindexes 01h.. in order (may omit vendor methods)
  std::int8_t default_method = 0;                     // 6098h after power-up
  HomingVendorMethods vendor_methods = HomingVendorMethods::None;
  std::vector<HardStopMethod> hard_stops;             // the vendor push methods (XinjeHardStop, TorqueLimit)
  // 607Ch applies only to 35/37; every other method makes the reference point 0.
  bool offset_only_for_current_position = false;
  // Every sensor stop is abrupt, 609Ah only accelerates; otherwise reversals decelerate with 609Ah
  // and the final stop is a servo lock.
  bool abrupt_sensor_stop = false;
  // Methods 33/34 run on 6099h-01h alone (a 6099h-02h of 0 is then no error); false: 6099h-02h.
  bool index_methods_use_switch_speed = true;
  // Alarm raised when homing is cancelled between home detection and completion ("" = none).
  std::string cancel_after_detection_alarm;
};

// A trigger source selectable for a touch-probe channel.
struct TouchProbeSource {
  std::uint8_t channel = 1;                           // 1 or 2
  std::uint8_t trigger_select = 0;                    // value of the channel's 60B8h trigger-select bits
                                                      // (bit 2 / 10; DS1000A-EC bits 3-2 / 11-10)
  std::int16_t source = 0;                            // 60D0h value when trigger_select picks 60D0h, else 0
  std::string name;                                   // e.g. "EXT1 (SI5)", "Z phase"
};

struct TouchProbeSpec {
  std::uint8_t channels = 0;                          // 0 = no touch probe
  bool rising_edge = false;
  bool falling_edge = false;
  bool both_edges_at_once = false;                    // rising and falling armed together
  bool continuous = false;                            // 60B8h bit1 = 1 (continuous) supported
  std::vector<TouchProbeSource> sources;
};

// --- Alarms and motors (profiles/<id>/alarms.yaml, motors.yaml) ----------------------------------

// What the drive does to the motor when the alarm occurs.
enum class AlarmReaction : std::uint8_t {
  None,            // no motor reaction (communication alarm only; PDS unchanged)
  ImmediateStop,   // immediate stop (torque-limited stop / dynamic brake)
  Deceleration,    // decelerate to stop, then disable
  FreeRun,         // power stage off at once, motor coasts
};

struct AlarmSpec {
  std::string code;                                   // vendor display code as printed: "80.4", "E-804", "FF01h"
  std::string name;                                   // original-language name as printed
  std::string name_en;                                // English
  std::uint16_t error_code = 0;                       // 603Fh value while active
  std::uint16_t emergency_code = 0;                   // error code sent in the EMCY message
  bool clearable = true;                              // can be reset by fault reset / alarm clear
  AlarmReaction reaction = AlarmReaction::None;
  std::uint16_t al_status_code = 0;                   // 0 = no AL status code
  bool history = true;                                // kept in the alarm history (10F3h / vendor list)
  bool warning = false;                               // a warning, not an alarm (no Fault state)
  std::string source;                                 // manual line(s), e.g. "L32567"
};

// A motor of the product's catalogue. Absent values are 0 (the manual does not give them).
struct MotorSpec {
  std::string model;
  std::string condition;                              // when ratings depend on it, e.g. "24 V supply" ("" = none)
  std::string source;                                 // manual line(s)
  double rated_power_w = 0;
  double rated_torque_nm = 0;                         // continuous (servo) or holding torque (stepper)
  double peak_torque_nm = 0;
  double rated_speed_rpm = 0;
  double max_speed_rpm = 0;
  double rated_current_a = 0;                         // rms (servo) / per phase (stepper)
  double torque_constant_nm_per_a = 0;
  double rotor_inertia_kgm2 = 0;                      // SI units (manuals print x10^-4 kg m^2 or g cm^2)
  std::uint32_t encoder_counts_per_rev = 0;
};

// --- CiA402 drive behaviour (profile.yaml key `drive`) --------------------------------------------

// One vendor parameter the drive reads a control-loop setting from, e.g. A6B Pr1.00 = 3100h
// (0.1/s). SI value = raw * scale; `fallback` (SI) when the product has no such object or it reads 0.
struct ParameterRef {
  std::uint16_t index = 0;                            // 0 = the product has none
  std::uint8_t subindex = 0;
  double scale = 1.0;
  double fallback = 0.0;
};

// Where the drive's control loops take their gains from.
struct ControlGainSpec {
  ParameterRef position_gain;                         // Kp, 1/s
  ParameterRef velocity_gain;                         // velocity-loop bandwidth, Hz
  ParameterRef velocity_integral;                     // velocity-loop integral time constant, s
  ParameterRef torque_filter;                         // torque command filter time constant, s
  ParameterRef inertia_ratio;                         // load / rotor inertia, as a ratio (1.0 = 100 %)
  ParameterRef velocity_feedforward;                  // 0..1
};

// The vendor alarm ("24.0", "E-100", "FF02h") the drive raises for each cause it can detect in
// simulation; "" = the product has no alarm for it (the cause then only shows in the statusword).
struct DriveAlarmCauses {
  std::string following_error;                        // position deviation beyond the alarm level
  std::string overspeed;                              // motor speed beyond the overspeed level
  std::string overload;                               // motor overload (thermal / I^2 t)
  std::string overtemperature;                        // drive or motor over-temperature
  std::string esm_change_while_enabled;               // ESM left Op while Operation enabled
  std::string no_mode_at_enable;                      // enable with 6060h = 6061h = 0 / bad mode
  std::string position_command_jump;                  // csp set-point step beyond the speed limit
  std::string position_range;                         // 607Ah outside 607Bh
  std::string limit_switch;                           // POT/NOT reached (products that alarm)
  std::string both_limit_switches;                    // both limits active / wrong direction
  std::string homing_error;                           // products with a homing alarm
  std::string encoder_error;                          // encoder communication lost
  std::string overvoltage;                            // DC bus over-voltage
  std::string undervoltage;                           // DC bus (PN) under-voltage
  std::string main_power_off;                         // main (power-stage) supply switched off
  std::string abort_connection;                       // main power lost while enabled with 6007h = 1
  // undervoltage / main_power_off are detected only while the power stage is on (servo on); with
  // the servo off the loss shows in 6041h bit 4 alone (A6B). false: detected in any state.
  bool supply_alarms_only_when_enabled = false;
};

enum class SoftLimitRule : std::uint8_t {
  Always,          // 607Dh acts whenever min < max (A6B once the position is established)
  AfterHoming,     // 607Dh acts only after a successful homing (DS1000A-EC, A6B incremental)
  Ignored,         // listed in the dictionary but not enforced (DS5C1)
};

enum class PositionRangeRule : std::uint8_t {
  Full,            // 80000000h..7FFFFFFFh, no wrap (A6B default, DS5C1: 607Bh ignored)
  Wrap,            // 6064h wraps between 607Bh-01h and -02h when they differ (DS1000A-EC)
};

enum class LimitSwitchRule : std::uint8_t {
  QuickStop,       // stop with the quick-stop ramp and refuse motion into the limit (no alarm)
  Alarm,           // raise DriveAlarmCauses::limit_switch
  ReportOnly,      // only shown in 60FDh
};

enum class BrakeRule : std::uint8_t {
  Automatic,       // the drive releases the brake on enable and engages it on disable
  Master,          // 60FEh-01h bit 0 under the 60FEh-02h mask (DS1000A-EC)
};

// Vendor levels the drive's own supervision uses.
struct DriveLevelSpec {
  ParameterRef following_error;                       // alarm level (A6B 3014h Pr0.14, DS5C1 P0-23, DS1000A 2108h)
  bool following_error_in_increments = false;         // level in encoder increments (else user units)
  bool following_error_in_revolutions = false;        // level in motor revolutions (DS5C1 P0-23, 0.01 rev)
  ParameterRef overspeed_rpm;                         // overspeed alarm level, r/min (0 / none: overspeed_factor * 6080h)
  ParameterRef overspeed_reverse_rpm;                 // reverse-direction level where the product has one (DS5C1 P3-22); none: overspeed_rpm
  ParameterRef overload;                              // servo I^2 t: load factor (1.0 = rated torque, continuous) that trips; 0: not supervised
  double overload_time_constant_s = 0.0;              // thermal time constant of the load factor
};

// The DS1000A-EC's closed-loop stepper settings (210Dh-2113h).
struct StepperSpec {
  ParameterRef loop_mode;                             // 0 closed, 1 open below switch speed, 2 open
  ParameterRef switch_speed_rpm;                      // open/closed switch speed
  ParameterRef run_current;                           // open-loop current, as a fraction of rated (scale to 0..1)
};

// Profile position (pp) set-point handling where the products differ.
struct ProfilePositionSpec {
  bool buffered_set_point = true;       // one set-point waits behind the executing one (A6B L15728-L15757);
                                        // false: a set-point given during a move without bit 5 is dropped (DS5C1 L3764)
  bool change_on_set_point = false;     // 6040h bit 9 honoured (DS1000A-EC L1729-L1738, L2081-L2086)
  bool sin2_profile = false;            // 6086h = 1 selects a sin^2 ramp (DS1000A-EC L1831-L1834)
  bool halt_discards_on_immediate = false;  // halt + bit 5 + new set-point drops the target and holds (DS1000A-EC L2111-L2117)
};

struct DriveSpec {
  std::uint32_t control_period_ns = 125000;           // internal position/velocity loop period
  bool stepper = false;                               // closed-loop stepper (open/closed-loop modes)
  double stopped_speed_rpm = 30.0;                    // "stopped" for stop sequences
  std::uint32_t mode_switch_ns = 0;                   // time a mode change takes (6061h lags)
  bool mode_switch_while_enabled = true;              // false: 6060h changes only act outside OE
  std::vector<std::pair<std::int8_t, std::int8_t>> forbidden_mode_switches;  // {from, to} in OE
  bool zero_mode_keeps_previous = true;               // writing 6060h = 0 after a mode keeps it
  bool halt_aborts_homing = true;
  bool offsets_honoured = true;                       // 60B0h/60B1h/60B2h added to targets
  double torque_mode_speed_cap_rpm = 0.0;             // speed cap in tq/cst (0 = 6080h only)
  double torque_clamp_permille = 0.0;                 // hard torque clamp (0 = motor peak)
  bool csp_clamps_to_max_speed = false;               // csp step beyond 6080h is clamped (else alarm)
  SoftLimitRule soft_limits = SoftLimitRule::Always;
  PositionRangeRule position_range = PositionRangeRule::Full;
  LimitSwitchRule limit_switches = LimitSwitchRule::QuickStop;
  BrakeRule brake = BrakeRule::Automatic;
  bool torque_off_input = false;                      // TO/STO input forces Switch on disabled
  std::uint32_t servo_on_delay_ns = 0;                // Switched on -> Operation enabled takes this long
  double overspeed_factor = 1.2;                      // overspeed alarm above factor * 6080h (when no vendor level)
  ProfilePositionSpec pp;
  ControlGainSpec gains;
  DriveLevelSpec levels;
  StepperSpec stepper_loop;
  DriveAlarmCauses alarms;
  VendorStopSpec vendor_stop;
  AlarmRulesSpec alarm_rules;
  IoRuleSet io_rules = IoRuleSet::Generic;
  SoftLimitStop soft_limit_stop = SoftLimitStop::AtLimit;
};

struct ProductProfile {
  std::string id;                    // the folder name under profiles/
  std::string title;                 // human name, e.g. "Panasonic MINAS-A6B"
  Identity identity;
  EscResources esc;
  Mailbox mailbox;
  MailboxSmRules mailbox_rules;
  std::vector<SyncManagerSpec> sync_managers;  // SII SyncManager category, in SM order
  bool has_bootstrap = false;                  // Boot state supported
  // Explicit Device ID (ETG.1000.6): AL control bit5 puts the device ID into AL status code 0x0134
  // and sets AL status bit5. A6B and DS1000A-EC support it, DS5C1 does not.
  bool explicit_device_id = false;
  AlStatusCodes al_codes;
  // SII General category: CoE details (bit0 SDO, 1 SDO info, 2 PDO assign, 3 PDO config,
  // 4 startup upload, 5 complete access), FoE details, ports.
  std::uint8_t coe_details = 0x0F;
  std::uint8_t foe_details = 0;
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

  // The alarm with vendor code `code` ("80.4", "E-804", "FF80h"), or nullptr.
  const AlarmSpec* find_alarm(std::string_view code) const {
    for (const AlarmSpec& a : alarms)
      if (a.code == code) return &a;
    return nullptr;
  }
};

}  // namespace vdrive::profile
