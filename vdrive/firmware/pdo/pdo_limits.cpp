#include "vdrive/firmware/pdo/pdo_limits.hpp"

#include <algorithm>
#include <utility>

namespace vdrive::firmware::pdo {

namespace {

constexpr DirectionLimits rx_limits(std::uint8_t objects, std::uint8_t entries,
                                    std::uint8_t assigned, std::uint16_t bytes) {
  return {kRxMappingFirst, objects, entries, assigned, bytes};
}
constexpr DirectionLimits tx_limits(std::uint8_t objects, std::uint8_t entries,
                                    std::uint8_t assigned, std::uint16_t bytes) {
  return {kTxMappingFirst, objects, entries, assigned, bytes};
}

// Panasonic MINAS-A6B: 1600h-1603h/1A00h-1A03h with 32 entries (L7064-L7077, L7203-L7216),
// 1C12h/1C13h 0-4 (L6892-L7000), at most 32 bytes per direction (L2861-L2865, Err85.0/85.1
// L33625-L33662). Writes only in PreOP and, for 01h+, only while 00h = 0, else 06010003h
// (L7004-L7006, L7060-L7062, L7168-L7170). 06040041h/06040042h are "not supported" (abort table
// L4411-L4552): mapping contents are only judged at PreOP->SafeOP.
PdoLimits a6b() {
  PdoLimits l;
  l.rx = rx_limits(4, 32, 4, 32);
  l.tx = tx_limits(4, 32, 4, 32);
  l.wrong_state_abort = od::SdoAbort::SubindexCannotBeWritten;
  l.mappable_checked_on_write = false;
  l.length_checked_on_write = false;
  return l;
}

// Xinje DS5C1: 1600h-1603h/1A00h-1A03h with 24 entries (L5597-L5602), 1C12h/1C13h 0-4
// (L5567-L5584), 32 bytes per direction from firmware 3791 (L2353, L2606-L2608); a larger mapping
// is E-850/E-851 at PreOP->SafeOP (L7134-L7135). 06010003h outside PreOP or with 00h != 0
// (L5587, L5622, L5654). Not-mappable objects: the manual names no code; the ETG 06040041h.
PdoLimits ds5c1() {
  PdoLimits l;
  l.rx = rx_limits(4, 24, 4, 32);
  l.tx = tx_limits(4, 24, 4, 32);
  l.wrong_state_abort = od::SdoAbort::SubindexCannotBeWritten;
  l.mappable_checked_on_write = true;
  l.length_checked_on_write = false;
  return l;
}

// DS1000A-EC: 1600h-1603h/1A00h-1A03h with 10 entries (13.2.1, L4455-L4475), 1C12h/1C13h 00h
// range 0-1 (L4673-L4697): one PDO per direction. The manual gives no byte limit, no state rule
// and no abort codes: a PDO holds at most 10 x 32 bits = 40 bytes, changes only in PreOP (ETG
// convention), and the ETG/CiA 301 codes answer (08000022h state, 06040041h, 06040042h).
PdoLimits ds1000a() {
  PdoLimits l;
  l.rx = rx_limits(4, 10, 1, 40);
  l.tx = tx_limits(4, 10, 1, 40);
  l.wrong_state_abort = od::SdoAbort::WrongState;
  l.mappable_checked_on_write = true;
  l.length_checked_on_write = true;
  return l;
}

DirectionLimits from_rules(std::uint16_t first_default,
                           const std::vector<profile::PdoObjectRule>& objects,
                           std::uint8_t max_assigned, std::uint16_t max_bytes) {
  DirectionLimits d;
  d.first_index = objects.empty() ? first_default : objects.front().index;
  d.mapping_objects = static_cast<std::uint8_t>(objects.size());
  for (const profile::PdoObjectRule& o : objects) d.max_entries = std::max(d.max_entries, o.max_entries);
  d.max_assigned = max_assigned;
  d.max_bytes = max_bytes;
  return d;
}

// ProductProfile::pdo_rules (profile.yaml `pdo_rules`), when the profile carries them.
PdoLimits from_profile(const profile::PdoRules& r) {
  PdoLimits l;
  l.rx = from_rules(kRxMappingFirst, r.rx_objects, r.max_rx_assigned, r.max_rx_bytes);
  l.tx = from_rules(kTxMappingFirst, r.tx_objects, r.max_tx_assigned, r.max_tx_bytes);
  // EsmStateSet bits (Init 01h, PreOp 02h, SafeOp 04h, Op 08h, Boot 10h) -> 1 << AlState.
  l.writable_states = 0;
  const std::pair<profile::EsmStateSet, AlState> states[] = {
      {profile::kStateInit, AlState::Init}, {profile::kStatePreOp, AlState::PreOp},
      {profile::kStateSafeOp, AlState::SafeOp}, {profile::kStateOp, AlState::Op},
      {profile::kStateBoot, AlState::Boot}};
  for (const auto& [bit, state] : states) {
    if (r.writable_states & bit) l.writable_states |= 1u << static_cast<unsigned>(state);
  }
  l.wrong_state_abort = static_cast<od::SdoAbort>(r.wrong_state_abort);
  l.sub0_must_be_zero = r.sub0_must_be_zero;
  l.mappable_checked_on_write = !r.checked_at_safeop;
  l.length_checked_on_write = !r.checked_at_safeop;
  return l;
}

}  // namespace

PdoLimits limits_for(const profile::ProductProfile& product) {
  if (!product.pdo_rules.rx_objects.empty() || !product.pdo_rules.tx_objects.empty()) {
    return from_profile(product.pdo_rules);
  }
  if (product.id == "a6b") return a6b();
  if (product.id == "ds5c1") return ds5c1();
  return ds1000a();  // the plain ETG rules, which the DS1000A-EC follows
}

WatchdogLimits watchdog_limits_for(const profile::ProductProfile& product) {
  const profile::WatchdogRule& rule = product.sync.watchdog;
  if (rule.min_cycles != 0 || rule.min_free_run_ns != 0) return {rule.min_cycles, rule.min_free_run_ns};
  // A6B Err81.4 (L33447-L33481): 2 x cycle in DC/SM2, 2 ms in free run.
  if (product.id == "a6b") return {2, 2'000'000};
  // DS5C1 E-814 (L7126): 2 x cycle time; free run not stated.
  if (product.id == "ds5c1") return {2, 0};
  return {};  // DS1000A-EC: no watchdog rule in the manual
}

}  // namespace vdrive::firmware::pdo
