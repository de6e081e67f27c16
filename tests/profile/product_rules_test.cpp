// The product rules of profile.yaml (drive.vendor_stop, drive.alarm_rules, drive.io_rules,
// drive.soft_limit_stop and the homing rule keys): what each product states, and how a bad value is
// refused naming the file, the line and the key.
#include <gtest/gtest.h>

#include <string>

#include "tests/profile/profile_text_edit.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

using test::at;
using test::embedded_texts;
using test::load_texts;
using test::LoadResult;
using test::ProductTexts;
using test::replace_once;

TEST(ProfileProductRules, EachProductStatesItsRules) {
  const ProductProfile a6b = load_profile("a6b");
  EXPECT_EQ(a6b.drive.vendor_stop.rule, VendorStopRule::Panasonic);
  EXPECT_EQ(a6b.drive.vendor_stop.servo_off.index, 0x3506);
  EXPECT_EQ(a6b.drive.vendor_stop.alarm.index, 0x3510);
  EXPECT_EQ(a6b.drive.vendor_stop.stop_torque.index, 0x3511);
  EXPECT_EQ(a6b.drive.vendor_stop.stop_time_ms.index, 0);
  EXPECT_EQ(a6b.drive.alarm_rules.error_register, ErrorRegisterRule::AlStatusDefined);
  EXPECT_TRUE(a6b.drive.alarm_rules.emergency_sub_code);
  EXPECT_TRUE(a6b.drive.alarm_rules.emergency_gated_by_10f3);
  EXPECT_EQ(a6b.drive.alarm_rules.history, AlarmHistoryKind::DiagnosisHistory);
  EXPECT_EQ(a6b.drive.alarm_rules.delayed_clear_code, "16.0");
  EXPECT_EQ(a6b.drive.alarm_rules.delayed_clear_after_ms, 10000u);
  EXPECT_EQ(a6b.drive.io_rules, IoRuleSet::A6B);
  EXPECT_EQ(a6b.drive.soft_limit_stop, SoftLimitStop::Ramp);
  EXPECT_EQ(a6b.homing.vendor_methods, HomingVendorMethods::ManufacturerOnly);
  EXPECT_TRUE(a6b.homing.hard_stops.empty());
  EXPECT_EQ(a6b.homing.cancel_after_detection_alarm, "27.7");

  const ProductProfile ds5c1 = load_profile("ds5c1");
  EXPECT_EQ(ds5c1.drive.vendor_stop.rule, VendorStopRule::Xinje);
  EXPECT_EQ(ds5c1.drive.vendor_stop.alarm.index, 0x201D);
  EXPECT_EQ(ds5c1.drive.vendor_stop.alarm.fallback, 2);
  EXPECT_EQ(ds5c1.drive.vendor_stop.stop_time_ms.fallback, 25);
  EXPECT_EQ(ds5c1.drive.alarm_rules.history, AlarmHistoryKind::XinjeMonitors);
  EXPECT_EQ(ds5c1.drive.io_rules, IoRuleSet::DS5C1);
  EXPECT_EQ(ds5c1.drive.soft_limit_stop, SoftLimitStop::AtLimit);
  EXPECT_EQ(ds5c1.homing.vendor_methods, HomingVendorMethods::XinjeHardStop);
  ASSERT_EQ(ds5c1.homing.hard_stops.size(), 2u);
  EXPECT_EQ(ds5c1.homing.hard_stops[1].method, -2);
  EXPECT_EQ(ds5c1.homing.hard_stops[1].direction, -1);
  EXPECT_TRUE(ds5c1.homing.hard_stops[1].push_at_zero_speed);
  EXPECT_TRUE(ds5c1.homing.offset_only_for_current_position);

  const ProductProfile ds1000a = load_profile("ds1000a");
  EXPECT_EQ(ds1000a.drive.vendor_stop.rule, VendorStopRule::None);
  EXPECT_EQ(ds1000a.drive.alarm_rules.error_register, ErrorRegisterRule::Cia301Class);
  EXPECT_EQ(ds1000a.drive.alarm_rules.history, AlarmHistoryKind::None);
  EXPECT_EQ(ds1000a.drive.io_rules, IoRuleSet::DS1000A);
  EXPECT_EQ(ds1000a.homing.vendor_methods, HomingVendorMethods::TorqueLimit);
  ASSERT_EQ(ds1000a.homing.hard_stops.size(), 4u);
  EXPECT_TRUE(ds1000a.homing.hard_stops[0].index_after);
  EXPECT_FALSE(ds1000a.homing.hard_stops[2].index_after);
  EXPECT_TRUE(ds1000a.homing.abrupt_sensor_stop);
  EXPECT_FALSE(ds1000a.homing.index_methods_use_switch_speed);
  EXPECT_TRUE(ds1000a.drive.stepper);
}

// One edit of product `id`'s profile.yaml; returns the load error.
struct Edit {
  ProductTexts texts;
  LoadResult result;
};

Edit edit(const std::string& id, const std::string& from, const std::string& to) {
  Edit e{embedded_texts(id), {}};
  e.texts.profile = replace_once(e.texts.profile, from, to);
  e.result = load_texts(id, e.texts);
  return e;
}

TEST(ProfileProductRules, UnknownRuleNamesListTheAcceptedOnes) {
  Edit e = edit("a6b", "    rule: panasonic", "    rule: siemens");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "rule: siemens") +
                                "drive.vendor_stop.rule: is 'siemens', expected one of none, panasonic, xinje");
  e = edit("ds5c1", "  io_rules: xinje_ds5c1", "  io_rules: ds5c1");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "io_rules: ds5c1") +
                                "drive.io_rules: is 'ds5c1', expected one of generic, minas_a6b, xinje_ds5c1, ds1000a_ec");
  e = edit("a6b", "  soft_limit_stop: ramp", "  soft_limit_stop: decelerate");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "soft_limit_stop: decelerate") +
                                "drive.soft_limit_stop: is 'decelerate', expected one of at_limit, ramp");
  e = edit("ds1000a", "    history: none", "    history: eeprom");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "history: eeprom") +
                                "drive.alarm_rules.history: is 'eeprom', expected one of none, diagnosis_history, "
                                "xinje_monitors");
  e = edit("ds1000a", "  vendor_methods: torque_limit", "  vendor_methods: push");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "vendor_methods: push") +
                                "homing.vendor_methods: is 'push', expected one of none, manufacturer_only, "
                                "xinje_hard_stop, torque_limit");
}

TEST(ProfileProductRules, VendorStopParametersFitTheRule) {
  Edit e = edit("ds1000a", "    servo_off: {index: 0, fallback: 0}", "    servo_off: {index: 0x201B, subindex: 0, fallback: 0}");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "servo_off: {index: 0x201B") +
                                "drive.vendor_stop.servo_off: names a parameter but rule is none (no vendor stop reads it)");
  e = edit("ds5c1", "    alarm: {index: 0x201D, subindex: 0, fallback: 2}", "    alarm: {index: 0, fallback: 2}");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "alarm: {index: 0, fallback: 2}") +
                                "drive.vendor_stop.alarm: is needed by a vendor stop rule (index 0 given)");
  e = edit("a6b", "servo_off: {index: 0x3506, subindex: 0, fallback: 0}", "servo_off: {index: 0x1006, subindex: 0, fallback: 0}");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "servo_off: {index: 0x1006") +
                                "drive.vendor_stop.servo_off.index: 0x1006 is not a vendor or profile object (2000h..FFFFh)");
  e = edit("a6b", "stop_torque: {index: 0x3511, subindex: 0, fallback: 0}", "stop_torque: {index: 0x3511, subindex: 0, fallback: 40000}");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "fallback: 40000") +
                                "drive.vendor_stop.stop_torque.fallback: expected a signed 16-bit integer");
}

TEST(ProfileProductRules, AlarmRulesMustBeConsistent) {
  Edit e = edit("ds5c1", "    emergency_gated_by_10f3: false", "    emergency_gated_by_10f3: true");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "emergency_gated_by_10f3: true") +
                                "drive.alarm_rules.emergency_gated_by_10f3: needs history: diagnosis_history (10F3h "
                                "holds the gate)");
  e = edit("a6b", R"(delayed_clear: {code: "16.0", after_ms: 10000})", R"(delayed_clear: {code: "16.0", after_ms: 0})");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "after_ms: 0}") +
                                "drive.alarm_rules.delayed_clear.after_ms: expected > 0 with an alarm code, 0 with code \"\"");
  e = edit("a6b", R"(delayed_clear: {code: "16.0", after_ms: 10000})", R"(delayed_clear: {code: "16.9", after_ms: 10000})");
  EXPECT_EQ(e.result.error,
            e.result.dir + "/profile.yaml: drive.alarm_rules.delayed_clear.code: '16.9' is not an alarm of alarms.yaml");
}

TEST(ProfileProductRules, HardStopRowsNameVendorMethodsOfTheProduct) {
  Edit e = edit("ds1000a", "- {method: -3, direction: negative", "- {method: 3, direction: negative");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "{method: 3,") +
                                "homing.hard_stops[2].method: expected a vendor method (< 0)");
  e = edit("ds5c1", "- {method: -2, direction: negative", "- {method: -3, direction: negative");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "{method: -3,") +
                                "homing.hard_stops[1].method: -3 is not one of methods");
  e = edit("ds5c1", "- {method: -2, direction: negative", "- {method: -1, direction: negative");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "{method: -1, direction: negative") +
                                "homing.hard_stops[1].method: -1 is listed twice");
  e = edit("ds5c1", "- {method: -2, direction: negative", "- {method: -2, direction: backward");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "direction: backward") +
                                "homing.hard_stops[1].direction: is 'backward', expected one of positive, negative");
  e = edit("ds5c1", "  vendor_methods: xinje_hard_stop", "  vendor_methods: manufacturer_only");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "hard_stops:") +
                                "homing.hard_stops: lists methods but vendor_methods is not xinje_hard_stop or torque_limit");
  e = edit("a6b", "  vendor_methods: manufacturer_only", "  vendor_methods: torque_limit");
  EXPECT_EQ(e.result.error, at(e.result, e.texts.profile, "hard_stops: []") +
                                "homing.hard_stops: is empty but vendor_methods pushes against a hard stop");
}

TEST(ProfileProductRules, CancelledHomingAlarmIsAnAlarmOfTheTable) {
  const Edit e = edit("a6b", R"(cancel_after_detection_alarm: "27.7")", R"(cancel_after_detection_alarm: "27.9")");
  EXPECT_EQ(e.result.error,
            e.result.dir + "/profile.yaml: homing.cancel_after_detection_alarm: '27.9' is not an alarm of alarms.yaml");
}

TEST(ProfileProductRules, RuleKeysAreRequired) {
  Edit e = edit("ds5c1", "  io_rules: xinje_ds5c1\n", "");
  EXPECT_NE(e.result.error.find("drive.io_rules: missing"), std::string::npos) << e.result.error;
  e = edit("a6b", "  abrupt_sensor_stop: false", "  abrupt_sensor_stops: false");
  EXPECT_NE(e.result.error.find("homing.abrupt_sensor_stop: missing"), std::string::npos) << e.result.error;
}

}  // namespace
}  // namespace vdrive::profile
