#pragma once
// Readers for the parts of a product beyond identity and SII: the profile.yaml
// sections sync, pdo_rules, modes, homing and touch_probe, and the files alarms.yaml and
// motors.yaml. Each reader checks what the data must satisfy on its own; check_consistency()
// checks the rules that tie sections together. Errors are ProfileError "<file>:<line>: <field>: ...".
#include <string>
#include <vector>

#include "vdrive/profile/product_profile.hpp"
#include "vdrive/profile/yaml_map_reader.hpp"

namespace vdrive::profile {

SyncSpec read_sync(YamlMapReader m);
PdoRules read_pdo_rules(YamlMapReader m);
ModesSpec read_modes(YamlMapReader m);
HomingSpec read_homing(YamlMapReader m);
TouchProbeSpec read_touch_probe(YamlMapReader m);
// `drive`: the CiA 402 behaviour (DriveSpec). `modes` is the product's modes section, which
// forbidden_mode_switches must name.
DriveSpec read_drive(YamlMapReader m, const ModesSpec& modes);
// drive.vendor_stop and drive.alarm_rules (product_rules.hpp).
VendorStopSpec read_vendor_stop(YamlMapReader m);
AlarmRulesSpec read_alarm_rules(YamlMapReader m);
// The homing keys beyond the method lists (vendor_methods, hard_stops and the flags), into `h`,
// whose methods the hard stops must be among.
void read_homing_rules(YamlMapReader& m, HomingSpec& h);

// Cross-section rules: default PDOs exist in pdo_rules and fit its limits; per-mode cycle limits
// name supported modes. `root` is profile.yaml's top level, used to point at the offending key.
void check_consistency(const ProductProfile& p, const YamlMapReader& root);

// alarms.yaml / motors.yaml: `text` is the file, `file` its name in messages, `id` the product
// (the file's `product:` must name it).
std::vector<AlarmSpec> parse_alarms(std::string_view id, const std::string& text, const std::string& file);
std::vector<MotorSpec> parse_motors(std::string_view id, const std::string& text, const std::string& file);
// drive.alarms, drive.alarm_rules and homing name only alarms of alarms.yaml (checked once both are
// read); `file` is profile.yaml.
void check_drive_alarms(const ProductProfile& p, const std::string& file);

// Parses `text` as YAML; a syntax error becomes a ProfileError naming file and line.
YAML::Node load_yaml(const std::string& text, const std::string& file);

}  // namespace vdrive::profile
