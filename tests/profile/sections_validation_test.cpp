// Bad sync / PDO-rule / mode / homing / touch-probe sections and bad alarms.yaml / motors.yaml are
// refused with a message naming the file, the line and the field.
#include <gtest/gtest.h>

#include <string>

#include "tests/profile/profile_text_edit.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

using test::line_of;
using test::LoadResult;
using test::replace_once;
using test::where;
using Texts = test::ProductTexts;

Texts embedded(std::string_view id) { return test::embedded_texts(id); }
LoadResult load(const std::string& id, const Texts& t) { return test::load_texts(id, t); }

TEST(ProfileSectionsValidation, UnmodifiedFilesLoad) {
  for (const char* id : {"a6b", "ds5c1", "ds1000a"}) EXPECT_EQ(load(id, embedded(id)).error, "") << id;
}

TEST(ProfileSectionsValidation, CycleTimesMustAscend) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "cycle_times_ns: [125000, 250000,", "cycle_times_ns: [250000, 125000,");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "cycle_times_ns: [250000") +
                         "sync.cycle_times_ns: expected ascending, distinct, non-zero cycle times");
}

TEST(ProfileSectionsValidation, ListElementOutOfRangeNamesTheElement) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "accepted_dc_activation: [0x00, 0x03]", "accepted_dc_activation: [0x00, 0x103]");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "accepted_dc_activation:") +
                         "sync.accepted_dc_activation[1]: expected an unsigned 8-bit integer");
}

TEST(ProfileSectionsValidation, DefaultSyncTypeMustBeAccepted) {
  Texts t = embedded("ds5c1");
  t.profile = replace_once(t.profile, "default_sync_type: 0x00                   # not in manual: ETG default free run",
                           "default_sync_type: 0x22");
  const LoadResult r = load("ds5c1", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "default_sync_type: 0x22") +
                         "sync.sm2.default_sync_type: is not one of accepted_sync_types");
}

TEST(ProfileSectionsValidation, InputSm2SyncTypeMustBeAnSm2ValueTheProductAccepts) {
  Texts t = embedded("ds5c1");
  t.profile = replace_once(t.profile, "input_sm2_sync_type: 0x01 ", "input_sm2_sync_type: 0x22 ");
  LoadResult r = load("ds5c1", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "input_sm2_sync_type: 0x22") +
                         "sync.input_sm2_sync_type: is not one of sm3.accepted_sync_types");
  t = embedded("a6b");
  t.profile = replace_once(t.profile, "input_sm2_sync_type: 0x22 ", "input_sm2_sync_type: 0x02 ");
  r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "input_sm2_sync_type: 0x02") +
                         "sync.input_sm2_sync_type: expected 0x01 or 0x22 (the 1C33h-01h value for "
                         "SM2-synchronous inputs)");
}

TEST(ProfileSectionsValidation, CounterSubindexesMustBeRealDistinctCounters) {
  Texts t = embedded("a6b");   // a6b: 0Bh-0Eh not supported (error_counters false)
  t.profile = replace_once(t.profile, "sm_event_missed_subindex: 0x00 ", "sm_event_missed_subindex: 0x0C ");
  LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "sm_event_missed_subindex: 0x0C") +
                         "sync.sm_event_missed_subindex: names a counter but sm2/sm3 error_counters is false");
  t = embedded("ds1000a");
  t.profile = replace_once(t.profile, "cycle_too_small_subindex: 0x0C ", "cycle_too_small_subindex: 0x20 ");
  r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "cycle_too_small_subindex: 0x20") +
                         "sync.cycle_too_small_subindex: expected 0 (not counted) or a counter subindex 0x0B-0x0E");
  t = embedded("ds1000a");
  t.profile = replace_once(t.profile, "cycle_too_small_subindex: 0x0C ", "cycle_too_small_subindex: 0x0B ");
  r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "cycle_too_small_subindex: 0x0B") +
                         "sync.cycle_too_small_subindex: is the same subindex as sm_event_missed_subindex");
}

TEST(ProfileSectionsValidation, ThresholdObjectAndThresholdValueExcludeEachOther) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "missed_sync_threshold: 0 ", "missed_sync_threshold: 3 ");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "missed_sync_threshold: 3") +
                         "sync.missed_sync_threshold: expected 0: missed_sync_threshold_object holds the threshold");
}

TEST(ProfileSectionsValidation, SyncBehaviourKeysAreRequired) {
  for (const char* key : {"missed_sync_threshold_object", "sync_error_count_object", "sync_types_follow_dc_activation",
                          "input_sm2_sync_type", "sm_event_missed_subindex", "cycle_too_small_subindex",
                          "sync_error_flag"}) {
    Texts t = embedded("ds5c1");
    const auto pos = t.profile.find(std::string("\n  ") + key + ":");
    ASSERT_NE(pos, std::string::npos) << key;
    t.profile.erase(pos, t.profile.find('\n', pos + 1) - pos);
    const LoadResult r = load("ds5c1", t);
    // A missing field points at the line of its mapping's key.
    const int sync_line = line_of(t.profile, "\nsync:") + 1;
    EXPECT_EQ(r.error, r.dir + "/profile.yaml:" + std::to_string(sync_line) + ": sync." + key + ": missing");
  }
}

TEST(ProfileSectionsValidation, CycleStepRangeMustBeMultiples) {
  Texts t = embedded("ds1000a");
  t.profile = replace_once(t.profile, "cycle_min_ns: 1000000 ", "cycle_min_ns: 1500000 ");
  const LoadResult r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "cycle_min_ns: 1500000") +
                         "sync.cycle_min_ns: expected a non-zero multiple of cycle_step_ns");
}

TEST(ProfileSectionsValidation, SupportedDriveModesMustMatchTheModeList) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "modes: [1, 3, 4, 6, 8, 9, 10]", "modes: [1, 3, 4, 6, 7, 8, 9, 10]");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "supported_drive_modes: 0x000003AD") +
                         "modes.supported_drive_modes: bits 0-9 are 0x3AD but modes give 0x3ED");
}

TEST(ProfileSectionsValidation, ListedHomingMethodMustBeAccepted) {
  Texts t = embedded("ds5c1");
  t.profile = replace_once(t.profile, "29, 30, 33, 34, 35, 37]\n  default_method",
                           "29, 30, 33, 34, 35, 37, -3]\n  default_method");
  const LoadResult r = load("ds5c1", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "  listed: [") +
                         "homing.listed: method -3 is listed but not in methods");
}

TEST(ProfileSectionsValidation, TouchProbeChannelBeyondTheCount) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "{channel: 2, trigger_select: 0, source: 0, name: \"EXT2 (SI6)\"}",
                           "{channel: 3, trigger_select: 0, source: 0, name: \"EXT2 (SI6)\"}");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "{channel: 3") +
                         "touch_probe.sources[2].channel: expected 1..channels");
}

TEST(ProfileSectionsValidation, DefaultMappingLargerThanTheLimit) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "max_rx_bytes: 32 ", "max_rx_bytes: 8 ");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "rx_pdos:") +
                         "rx_pdos: default mapping is 9 bytes, pdo_rules allows 8");
}

TEST(ProfileSectionsValidation, MoreAssignableThanMappingObjects) {
  Texts t = embedded("ds1000a");
  t.profile = replace_once(t.profile, "max_tx_assigned: 1 ", "max_tx_assigned: 5 ");
  const LoadResult r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "max_tx_assigned: 5") +
                         "pdo_rules.max_tx_assigned: exceeds the number of tx_objects");
}

TEST(ProfileSectionsValidation, WritableStateName) {
  Texts t = embedded("a6b");
  t.profile = replace_once(t.profile, "writable_states: [preop]", "writable_states: [pre-op]");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "profile.yaml", t.profile, "writable_states: [pre-op]") +
                         "writable_states[0]: expected one of init, preop, safeop, op, boot");
}

TEST(ProfileSectionsValidation, MissingSectionIsAnError) {
  Texts t = embedded("ds5c1");
  const auto pos = t.profile.find("\ntouch_probe:");
  ASSERT_NE(pos, std::string::npos);
  t.profile.resize(pos + 1);
  const LoadResult r = load("ds5c1", t);
  EXPECT_NE(r.error.find("profile.yaml:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(": touch_probe: missing"), std::string::npos) << r.error;
}

TEST(ProfileSectionsValidation, AlarmReactionMustBeKnown) {
  Texts t = embedded("ds1000a");
  t.alarms = replace_once(t.alarms, "error_code: 0xFF03, emergency_code: 0xFF03, clearable: true, reaction: free_run",
                          "error_code: 0xFF03, emergency_code: 0xFF03, clearable: true, reaction: coast");
  const LoadResult r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "alarms.yaml", t.alarms, "reaction: coast") +
                         "alarms[5].reaction: expected one of none, immediate_stop, deceleration, free_run");
}

TEST(ProfileSectionsValidation, AlarmCodeTwiceIsAnError) {
  Texts t = embedded("ds1000a");
  t.alarms = replace_once(t.alarms, "{code: \"7500h\"", "{code: \"5530h\"");
  const LoadResult r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "alarms.yaml", t.alarms, "{code: \"5530h\", name: \"内部") +
                         "alarms[1].code: '5530h' appears twice");
}

TEST(ProfileSectionsValidation, AlarmSourceMustCiteALine) {
  Texts t = embedded("a6b");
  t.alarms = replace_once(t.alarms, "source: L32604}", "source: table 8-1}");
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, where(r, "alarms.yaml", t.alarms, "source: table 8-1") +
                         "alarms[4].source: expected manual lines, e.g. L32596 or L4318-L4322");
}

TEST(ProfileSectionsValidation, AlarmTableOfAnotherProduct) {
  Texts t = embedded("ds5c1");
  t.alarms = embedded("a6b").alarms;
  const LoadResult r = load("ds5c1", t);
  EXPECT_EQ(r.error, where(r, "alarms.yaml", t.alarms, "product: a6b") +
                         "product: expected 'ds5c1' (the directory name)");
}

TEST(ProfileSectionsValidation, MissingAlarmFileIsNamed) {
  Texts t = embedded("a6b");
  t.alarms.clear();
  const LoadResult r = load("a6b", t);
  EXPECT_EQ(r.error, r.dir + "/alarms.yaml: cannot read (every product has profile.yaml, alarms.yaml and motors.yaml)");
}

TEST(ProfileSectionsValidation, MotorPeakBelowRatedTorque) {
  Texts t = embedded("ds1000a");
  t.motors = replace_once(t.motors, "rated_torque_nm: 0.300, rated_speed_rpm: 500,",
                          "rated_torque_nm: 0.300, peak_torque_nm: 0.2, rated_speed_rpm: 500,");
  const LoadResult r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "motors.yaml", t.motors, "peak_torque_nm: 0.2") +
                         "motors[2].peak_torque_nm: is below rated_torque_nm");
}

TEST(ProfileSectionsValidation, MotorNumberMustBeANonNegativeNumber) {
  Texts t = embedded("ds1000a");
  t.motors = replace_once(t.motors, "rated_torque_nm: 0.106, rated_speed_rpm: 800,",
                          "rated_torque_nm: -0.106, rated_speed_rpm: 800,");
  const LoadResult r = load("ds1000a", t);
  EXPECT_EQ(r.error, where(r, "motors.yaml", t.motors, "rated_torque_nm: -0.106") +
                         "motors[0].rated_torque_nm: expected a number >= 0");
}

}  // namespace
}  // namespace vdrive::profile
