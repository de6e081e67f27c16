#pragma once
// A product's drive modes (6502h/6060h), homing methods (6098h/60E3h) and touch probe.
#include <cstdint>
#include <string>
#include <vector>

#include "vdrive/profile/product_rules.hpp"

namespace vdrive::profile {

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

}  // namespace vdrive::profile
