#include "vdrive/firmware/pdo/pdo_limits.hpp"

#include <algorithm>
#include <utility>

namespace vdrive::firmware::pdo {

namespace {

DirectionLimits from_rules(std::uint16_t first_default,
                           const std::vector<profile::PdoObjectRule>& objects,
                           std::uint8_t max_assigned, std::uint16_t max_bytes) {
  DirectionLimits d;
  d.first_index = first_default;
  d.last_index = static_cast<std::uint16_t>(first_default - 1);  // none
  if (!objects.empty()) {
    d.first_index = d.last_index = objects.front().index;
    for (const profile::PdoObjectRule& o : objects) {
      d.first_index = std::min(d.first_index, o.index);
      d.last_index = std::max(d.last_index, o.index);
    }
  }
  for (const profile::PdoObjectRule& o : objects) d.max_entries = std::max(d.max_entries, o.max_entries);
  d.max_assigned = max_assigned;
  d.max_bytes = max_bytes;
  return d;
}

PdoLimits from_profile(const profile::PdoRules& r) {
  PdoLimits l;
  l.rx = from_rules(kRxMappingFirst, r.rx_objects, r.max_rx_assigned, r.max_rx_bytes);
  l.tx = from_rules(kTxMappingFirst, r.tx_objects, r.max_tx_assigned, r.max_tx_bytes);
  // EsmStateSet bits (Init 01h, PreOp 02h, SafeOp 04h, Op 08h, Boot 10h) -> 1 << ecat::AlState.
  l.writable_states = 0;
  const std::pair<profile::EsmStateSet, ecat::AlState> states[] = {
      {profile::kStateInit, ecat::AlState::Init}, {profile::kStatePreOp, ecat::AlState::PreOp},
      {profile::kStateSafeOp, ecat::AlState::SafeOp}, {profile::kStateOp, ecat::AlState::Op},
      {profile::kStateBoot, ecat::AlState::Boot}};
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

// ProductProfile::pdo_rules (profile.yaml `pdo_rules`).
PdoLimits limits_for(const profile::ProductProfile& product) { return from_profile(product.pdo_rules); }

// ProductProfile::sync.watchdog (profile.yaml `sync.watchdog`).
WatchdogLimits watchdog_limits_for(const profile::ProductProfile& product) {
  const profile::WatchdogRule& rule = product.sync.watchdog;
  return {rule.min_cycles, rule.min_free_run_ns};
}

}  // namespace vdrive::firmware::pdo
