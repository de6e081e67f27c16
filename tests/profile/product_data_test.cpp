// The rest of each product as data: sync, PDO rules, modes, homing, touch probe,
// alarms and motors, spot-checked against the manuals. Each expectation cites the manual line that
// gives the value (a6b: panasonic-minas-a6b-ethercat-spec.zh.txt, ds5c1: xinje-ds5c1-user-manual.zh.md,
// ds1000a: ds1000a-ec-manual.ja.txt, all in /work/shared/seeds/).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "vdrive/profile/profile_loader.hpp"

namespace vdrive::profile {
namespace {

const AlarmSpec& alarm(const ProductProfile& p, const std::string& code) {
  const AlarmSpec* a = p.find_alarm(code);
  if (!a) throw std::runtime_error(p.id + ": no alarm " + code);
  return *a;
}

const MotorSpec& motor(const ProductProfile& p, const std::string& model, const std::string& condition = {}) {
  const auto it = std::find_if(p.motors.begin(), p.motors.end(),
                               [&](const MotorSpec& m) { return m.model == model && m.condition == condition; });
  if (it == p.motors.end()) throw std::runtime_error(p.id + ": no motor " + model);
  return *it;
}

bool has(const std::vector<std::int8_t>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

// ---------------------------------------------------------------------------------------------- a6b

TEST(ProfileProductData, A6bSync) {
  const ProductProfile p = load_profile("a6b");
  const SyncSpec& s = p.sync;
  EXPECT_TRUE(s.free_run && s.sm2_event && s.dc_sync0);  // L2838-L2842
  EXPECT_FALSE(s.dc_sync1);                              // 0981h 011b only, no SYNC1 (L33488-L33492)
  EXPECT_EQ(s.cycle_times_ns, (std::vector<std::uint32_t>{125000, 250000, 500000, 1000000, 2000000, 4000000,
                                                          8000000, 10000000}));  // L2846, L33357-L33359
  ASSERT_EQ(s.mode_min_cycle.size(), 3u);                // pp, pv, tq not at 125 us (L2848)
  for (const ModeCycleLimit& l : s.mode_min_cycle) {
    EXPECT_TRUE(l.mode == 1 || l.mode == 3 || l.mode == 4) << int(l.mode);
    EXPECT_EQ(l.min_cycle_ns, 250000u);
  }
  EXPECT_EQ(s.free_run_min_interval_ns, 250000u);        // L4155
  EXPECT_EQ(s.sm2.supported_sync_types, 0x0007);         // L7813-L7843
  EXPECT_EQ(s.sm3.supported_sync_types, 0x0027);         // L8321
  EXPECT_EQ(s.sm2.min_cycle_time_ns, 125000u);           // L7870
  EXPECT_EQ(s.sm2.calc_and_copy_time_ns, 25000u);        // L7890
  EXPECT_EQ(s.sm3.calc_and_copy_time_ns, 45000u);        // L8123
  EXPECT_EQ(s.sm2.delay_time_ns, 0u);                    // L7907
  EXPECT_EQ(s.sm3.accepted_sync_types, (std::vector<std::uint16_t>{0x00, 0x02, 0x22}));  // L7990-L7998
  EXPECT_FALSE(s.sm2.shift_time_writable);               // 1C32h-03h ro, not supported (L7805-L7807)
  EXPECT_TRUE(s.sm3.shift_time_writable);                // 1C33h-03h rw (L8044)
  EXPECT_EQ(s.input_shift.step_ns, 125000u);             // L8048
  EXPECT_EQ(s.input_shift.max_ns, 3875000u);             // L8315
  EXPECT_EQ(s.watchdog.min_cycles, 2);                   // Err81.4 (L33457-L33459)
  EXPECT_EQ(s.watchdog.min_free_run_ns, 2000000u);       // L33465
  EXPECT_EQ(s.pll_lock_timeout_ns, 1000000000u);         // Err80.3 (L33067)
  EXPECT_EQ(s.accepted_dc_activation, (std::vector<std::uint8_t>{0x00, 0x03}));  // Err81.5
  EXPECT_TRUE(s.sync_types_follow_dc_activation);        // 1C32h/1C33h-01h from 0981h (L7750-L7780, L8000-L8030)
  EXPECT_EQ(s.input_sm2_sync_type, 0x22);                // 1C33h-01h 22h = SM2 (L7998)
  EXPECT_EQ(s.missed_sync_threshold_object, 0x3742);     // Err80.7 threshold, bits 3-0 (L33248-L33264)
  EXPECT_EQ(s.sync_error_count_object, 0x4F78);          // L32136-L32142
  EXPECT_EQ(s.sm_event_missed_subindex, 0);              // not supported (L7922-L7923)
  EXPECT_EQ(s.cycle_too_small_subindex, 0);              // not supported (L7917-L7918)
  EXPECT_FALSE(s.sync_error_flag);                       // 20h not supported (L7937-L7938)
  EXPECT_EQ(p.complete_access_abort, 0x06010000u);       // abort table has no 06010004h (L4411-L4552)
}

TEST(ProfileProductData, A6bPdoRulesModesHomingTouchProbe) {
  const ProductProfile p = load_profile("a6b");
  ASSERT_EQ(p.pdo_rules.rx_objects.size(), 4u);          // 1600h-1603h (L7052-L7160)
  ASSERT_EQ(p.pdo_rules.tx_objects.size(), 4u);          // 1A00h-1A03h (L7191-L7299)
  EXPECT_EQ(p.pdo_rules.rx_objects.back().index, 0x1603);
  EXPECT_EQ(p.pdo_rules.tx_objects[0].max_entries, 32);  // 00h range 0-32 (L7204)
  EXPECT_EQ(p.pdo_rules.max_rx_assigned, 4);             // L2863
  EXPECT_EQ(p.pdo_rules.max_rx_bytes, 32);               // L2865
  EXPECT_EQ(p.pdo_rules.max_tx_bytes, 32);               // L2865
  EXPECT_EQ(p.pdo_rules.writable_states, kStatePreOp);   // L7060
  EXPECT_EQ(p.pdo_rules.wrong_state_abort, 0x06010003u); // L7170
  EXPECT_EQ(p.modes.supported_drive_modes, 0x000003ADu); // 6502h (L10251-L10263)
  EXPECT_FALSE(has(p.modes.modes, 7));                   // ip not supported (L17125-L17137)
  ASSERT_EQ(p.homing.listed.size(), 36u);                // 60E3h-00h = 36 (L18264)
  EXPECT_EQ(p.homing.listed[0x20 - 1], 37);              // 60E3h-20h = 37 (L18370)
  EXPECT_EQ(p.homing.listed[0x24 - 1], -4);              // 60E3h-24h = -4 (L18378)
  EXPECT_FALSE(has(p.homing.methods, 15));               // 15, 16 reserved (L17785-L17890)
  EXPECT_EQ(p.touch_probe.channels, 2);                  // "Touch Probe 2ch" (L2834)
  EXPECT_TRUE(p.touch_probe.rising_edge && p.touch_probe.falling_edge);  // L2834
  EXPECT_TRUE(std::any_of(p.touch_probe.sources.begin(), p.touch_probe.sources.end(), [](const TouchProbeSource& s) {
    return s.channel == 2 && s.trigger_select == 1 && s.name == "Z phase";  // 60B8h bit10 = 1 (L24690-L24706)
  }));
}

TEST(ProfileProductData, A6bAlarmsAndMotor) {
  const ProductProfile p = load_profile("a6b");
  EXPECT_GE(p.alarms.size(), 100u);                      // 8-1 lists ~110 codes (L32596-L32904)
  const AlarmSpec& pdo_watchdog = alarm(p, "80.4");      // L32604
  EXPECT_EQ(pdo_watchdog.al_status_code, 0x001B);
  EXPECT_EQ(pdo_watchdog.error_code, 0xFF50);            // FF00h + 80 (L33980-L33992)
  EXPECT_EQ(pdo_watchdog.reaction, AlarmReaction::ImmediateStop);
  EXPECT_EQ(alarm(p, "81.7").error_code, 0xA000);        // exception (L33996)
  EXPECT_EQ(alarm(p, "81.7").emergency_code, 0xA000);    // L4889-L4960
  EXPECT_EQ(alarm(p, "85.1").error_code, 0xFF55);        // example FF55h (L33990)
  EXPECT_EQ(alarm(p, "12.0").error_code, 0xFF0C);        // example FF0Ch (L33988)
  EXPECT_FALSE(alarm(p, "85.3").clearable);              // SII EEPROM error (L32630)
  EXPECT_EQ(alarm(p, "85.3").al_status_code, 0x0051);
  EXPECT_FALSE(alarm(p, "88.0").history);                // L32632-L32637
  EXPECT_EQ(alarm(p, "81.0").reaction, AlarmReaction::FreeRun);  // immediate stop "No" (L32610)
  EXPECT_EQ(alarm(p, "96.8").name_en, "Control unit error protection 7");  // "96 2-8 ... 1～7" (L32900)
  ASSERT_EQ(p.motors.size(), 1u);
  EXPECT_EQ(p.motors[0].encoder_counts_per_rev, 8388608u);  // 23 bit/r (L28631, L28790)
}

// -------------------------------------------------------------------------------------------- ds5c1

TEST(ProfileProductData, Ds5c1SyncAndPdoRules) {
  const ProductProfile p = load_profile("ds5c1");
  EXPECT_EQ(p.sync.cycle_times_ns,
            (std::vector<std::uint32_t>{1000000, 2000000, 4000000, 8000000, 10000000}));  // 3791+ (L2350)
  EXPECT_EQ(p.sync.sm2.supported_sync_types, 0x0007);    // L5672-L5676
  EXPECT_EQ(p.sync.sm3.accepted_sync_types, (std::vector<std::uint16_t>{0x00, 0x01, 0x02}));  // E-816 (L7128)
  EXPECT_EQ(p.sync.accepted_dc_activation, (std::vector<std::uint8_t>{0x00, 0x03}));        // E-815 (L7127)
  EXPECT_EQ(p.sync.watchdog.min_cycles, 2);              // E-814 (L7126)
  EXPECT_EQ(p.sync.pll_lock_timeout_ns, 1000000000u);    // E-803 (L7116)
  EXPECT_EQ(p.pdo_rules.rx_objects[0].max_entries, 24);  // subindex 01h-18h (L5622)
  EXPECT_EQ(p.pdo_rules.max_tx_assigned, 4);             // L2352
  EXPECT_EQ(p.pdo_rules.max_rx_bytes, 32);               // 3791+ (L2353)
  EXPECT_EQ(p.pdo_rules.wrong_state_abort, 0x06010003u); // L5587
  EXPECT_FALSE(p.sync.sync_types_follow_dc_activation);  // not in manual
  EXPECT_EQ(p.sync.input_sm2_sync_type, 0x01);           // 1C33h-01h 01h = SM2 (L5706-L5707)
  EXPECT_EQ(p.sync.sm_event_missed_subindex, 0);         // 0Bh-0Eh "不支持" (L5687-L5694)
  EXPECT_TRUE(p.sync.sync_error_flag);                   // 20h Sync error (L5695)
  EXPECT_EQ(p.sync.missed_sync_threshold_object, 0);
  EXPECT_EQ(p.complete_access_abort, 0x06010004u);       // not in manual: ETG.1000.6
}

TEST(ProfileProductData, Ds5c1ModesHomingTouchProbe) {
  const ProductProfile p = load_profile("ds5c1");
  EXPECT_EQ(p.modes.supported_drive_modes, 0x000003ADu); // 6502h bits (L6060-L6075)
  EXPECT_TRUE(has(p.homing.methods, -1) && has(p.homing.methods, -2));  // from 3791 (L3547)
  EXPECT_EQ(p.homing.listed.size(), 32u);                // 60E3h 01h-20h (L3445-L3491)
  EXPECT_FALSE(has(p.homing.listed, -1));
  EXPECT_EQ(p.homing.listed.back(), 37);                 // 60E3h-20h = 37 (L3491)
  EXPECT_EQ(p.touch_probe.channels, 2);                  // L2348
  EXPECT_FALSE(p.touch_probe.both_edges_at_once);        // L4566
  for (const TouchProbeSource& s : p.touch_probe.sources)
    EXPECT_EQ(s.trigger_select, 0) << s.name;            // Z phase "not supported" (L10056, L10068)
}

TEST(ProfileProductData, Ds5c1AlarmsAndMotors) {
  const ProductProfile p = load_profile("ds5c1");
  const AlarmSpec& sm23 = alarm(p, "E-817");             // L7129-L7133
  EXPECT_EQ(sm23.error_code, 0xA000);                    // L2557
  EXPECT_EQ(sm23.al_status_code, 0x001D);
  EXPECT_EQ(alarm(p, "E-850").error_code, 0xFF55);       // example 55h = 85d (L2557)
  EXPECT_EQ(alarm(p, "E-850").al_status_code, 0x0024);   // L7134
  EXPECT_EQ(alarm(p, "E-030").error_code, 0xFF03);       // example FF03h (L2557)
  EXPECT_EQ(alarm(p, "E-030").reaction, AlarmReaction::FreeRun);     // "伺服 off" (L7171)
  EXPECT_EQ(alarm(p, "E-022").reaction, AlarmReaction::Deceleration);  // "伺服 run" (L7164)
  EXPECT_TRUE(alarm(p, "E-022").history);                // L7164
  EXPECT_FALSE(alarm(p, "E-021").history);               // L7163
  EXPECT_FALSE(alarm(p, "E-280").clearable);             // L7214
  EXPECT_FALSE(alarm(p, "E-899").clearable);             // contact the dealer (L7139)
  EXPECT_EQ(alarm(p, "E-811").al_status_code, 0x0016);   // L7125
  const MotorSpec& big = motor(p, "MS-220STE-TL70015B□-411P0-XJ");  // L1304
  EXPECT_DOUBLE_EQ(big.rated_torque_nm, 70.0);           // 70015 (L462)
  EXPECT_DOUBLE_EQ(big.rated_speed_rpm, 1500.0);
  EXPECT_DOUBLE_EQ(big.rated_power_w, 11000.0);          // 11P0 (L472)
}

// ------------------------------------------------------------------------------------------ ds1000a

TEST(ProfileProductData, Ds1000aSyncAndPdoRules) {
  const ProductProfile p = load_profile("ds1000a");
  EXPECT_TRUE(p.sync.cycle_times_ns.empty());
  EXPECT_EQ(p.sync.cycle_step_ns, 1000000u);             // 1 ms steps (L691-L693)
  EXPECT_EQ(p.sync.cycle_min_ns, 1000000u);              // at least 1 ms (L3409)
  EXPECT_TRUE(p.sync.sm2_event && p.sync.dc_sync0);      // L3407
  EXPECT_EQ(p.sync.sm2.min_cycle_time_ns, 1000000u);     // L4730
  EXPECT_EQ(p.sync.sm3.calc_and_copy_time_ns, 125000u);  // L4769
  EXPECT_EQ(p.sync.sm2.supported_sync_types, 0);         // printed 0 (L4728)
  EXPECT_FALSE(p.sync.sm2.cycle_time_writable);          // 02h ro (L4705)
  EXPECT_TRUE(p.sync.sm2.error_counters);                // 0Bh-0Dh, 20h (L4742-L4753)
  EXPECT_EQ(p.sync.sm_event_missed_subindex, 0x0B);      // L4742
  EXPECT_EQ(p.sync.cycle_too_small_subindex, 0x0C);      // L4744
  EXPECT_TRUE(p.sync.sync_error_flag);                   // L4753
  EXPECT_EQ(p.sync.input_sm2_sync_type, 0x22);           // not in manual: ETG.1020
  EXPECT_EQ(p.complete_access_abort, 0x06010004u);       // not in manual: ETG.1000.6
  EXPECT_EQ(p.pdo_rules.rx_objects[2].max_entries, 10);  // 0-10 (L4509)
  EXPECT_EQ(p.pdo_rules.max_rx_assigned, 1);             // 1C12h-00h 0-1 (L4677)
  EXPECT_FALSE(p.pdo_rules.byte_aligned_total);          // 1600h default is 15 bytes (L4453-L4477)
}

TEST(ProfileProductData, Ds1000aModesHomingTouchProbe) {
  const ProductProfile p = load_profile("ds1000a");
  EXPECT_EQ(p.modes.supported_drive_modes, 0x000003EDu); // L5226
  EXPECT_TRUE(has(p.modes.modes, 7));                    // ip (L1580-L1590)
  ASSERT_EQ(p.homing.listed.size(), 36u);                // 60E3h-00h = 36 (L5118)
  EXPECT_EQ(p.homing.listed.back(), -4);                 // 60E3h-24h (L5118-L5192)
  const auto interlock = std::find_if(p.touch_probe.sources.begin(), p.touch_probe.sources.end(),
                                      [](const TouchProbeSource& s) { return s.source == -4; });
  ASSERT_NE(interlock, p.touch_probe.sources.end());
  EXPECT_EQ(interlock->name, "Interlock (TO inverted)"); // L3767
  EXPECT_EQ(interlock->trigger_select, 2);               // 10b = 60D0h (L3623)
  EXPECT_TRUE(std::none_of(p.touch_probe.sources.begin(), p.touch_probe.sources.end(),
                           [](const TouchProbeSource& s) { return s.source == 5; }));  // Z not supported (L3785)
}

TEST(ProfileProductData, Ds1000aAlarmsAndMotors) {
  const ProductProfile p = load_profile("ds1000a");
  EXPECT_EQ(p.alarms.size(), 10u);                       // chapter 12 table (L4318-L4392)
  EXPECT_EQ(alarm(p, "FF80h").error_code, 0xFF80);       // ESM error (L4386)
  EXPECT_FALSE(alarm(p, "5530h").clearable);             // repair (L4318)
  EXPECT_TRUE(alarm(p, "FF02h").clearable);
  EXPECT_EQ(alarm(p, "8312h").reaction, AlarmReaction::FreeRun);  // 605Eh initial 0 (L4907)
  const MotorSpec& stm42 = motor(p, "STM42W100A", "24 V supply, high-speed mode");  // L5833-L5837
  EXPECT_DOUBLE_EQ(stm42.rated_torque_nm, 0.300);
  EXPECT_DOUBLE_EQ(stm42.rated_speed_rpm, 500.0);
  EXPECT_EQ(stm42.encoder_counts_per_rev, 16000u);
  EXPECT_DOUBLE_EQ(motor(p, "STM28W100A", "48 V supply, high-speed mode").rated_speed_rpm, 1800.0);  // L5830
  EXPECT_DOUBLE_EQ(motor(p, "STM28W100A", "24 V supply, high-speed mode").max_speed_rpm, 3000.0);  // L5831
}

// ------------------------------------------------------------------------------------------ helpers

TEST(ProfileProductData, CycleAcceptanceFollowsListOrStep) {
  const ProductProfile a6b = load_profile("a6b");
  EXPECT_TRUE(a6b.sync.accepts_cycle(125000));           // L2846
  EXPECT_FALSE(a6b.sync.accepts_cycle(3000000));         // not in the list (Err81.0, L33357-L33359)
  EXPECT_EQ(a6b.sync.min_cycle_for_mode(1), 250000u);    // pp (L2848)
  EXPECT_EQ(a6b.sync.min_cycle_for_mode(8), 125000u);    // csp: the product minimum
  const ProductProfile ds1000a = load_profile("ds1000a");
  EXPECT_TRUE(ds1000a.sync.accepts_cycle(3000000));      // any 1 ms multiple (L691-L693)
  EXPECT_FALSE(ds1000a.sync.accepts_cycle(1500000));
  EXPECT_FALSE(ds1000a.sync.accepts_cycle(0));
  EXPECT_EQ(ds1000a.find_alarm("E-804"), nullptr);       // a DS5C1 code is not a DS1000A-EC alarm
}

// ------------------------------------------------------------------------------------ all products

class EveryProduct : public ::testing::TestWithParam<std::string> {};

// An alarm's AL status code is one the product's ESM reports (al_codes), so firmware and table agree.
TEST_P(EveryProduct, AlarmAlStatusCodesAreTheProductsCodes) {
  const ProductProfile p = load_profile(GetParam());
  const AlStatusCodes& c = p.al_codes;
  const std::set<std::uint16_t> esm = {c.invalid_transition, c.unknown_state, c.bootstrap_not_supported,
                                       c.invalid_mailbox_config, c.invalid_boot_mailbox_config, c.sync_watchdog,
                                       c.invalid_output_config, c.invalid_input_config, c.invalid_watchdog_config,
                                       c.invalid_input_mapping, c.invalid_output_mapping, c.sync_mode_not_supported,
                                       c.sync_error, c.no_sync_error, c.invalid_dc_sync_config, c.pll_error,
                                       c.invalid_sync_cycle_time, c.eeprom_error};
  for (const AlarmSpec& a : p.alarms) {
    if (a.al_status_code != 0) {
      EXPECT_TRUE(esm.contains(a.al_status_code)) << a.code;
    }
  }
}

// Default mapping sizes stay inside the product's PDO limits; every sync cycle limit is reachable.
TEST_P(EveryProduct, DefaultMappingFitsTheRules) {
  const ProductProfile p = load_profile(GetParam());
  unsigned rx_bits = 0;
  for (const PdoSpec& pdo : p.rx_pdos)
    for (const PdoEntrySpec& e : pdo.entries) rx_bits += e.bit_length;
  EXPECT_GT(rx_bits, 0u);
  EXPECT_LE(rx_bits / 8, p.pdo_rules.max_rx_bytes);
  EXPECT_GE(p.sync.cycle_max_ns, p.sync.cycle_min_ns);
  EXPECT_FALSE(p.alarms.empty());
  EXPECT_FALSE(p.motors.empty());
}

INSTANTIATE_TEST_SUITE_P(Products, EveryProduct, ::testing::Values("a6b", "ds5c1", "ds1000a"));

}  // namespace
}  // namespace vdrive::profile
