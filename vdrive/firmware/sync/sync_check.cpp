// PreOp->SafeOp synchronisation check; see sync_check.hpp.
#include "vdrive/firmware/sync/sync_check.hpp"

#include <algorithm>

namespace vdrive::firmware::sync {
namespace {

using profile::SyncType;

bool accepted(const std::vector<std::uint16_t>& values, std::uint16_t v) {
  return std::find(values.begin(), values.end(), v) != values.end();
}

bool dc_on(const SyncSettings& s) { return (s.dc_activation & kDcActivationMask) == kDcCyclicSync0; }

bool mode_supported(const profile::SyncSpec& spec, SyncMode mode) {
  switch (mode) {
    case SyncMode::FreeRun: return spec.free_run;
    case SyncMode::Sm2Event: return spec.sm2_event;
    case SyncMode::DcSync0: return spec.dc_sync0;
  }
  return false;
}

SyncMode mode_of(std::uint16_t output_sync_type) {
  switch (output_sync_type) {
    case static_cast<std::uint16_t>(SyncType::Sm2Event): return SyncMode::Sm2Event;
    case static_cast<std::uint16_t>(SyncType::DcSync0): return SyncMode::DcSync0;
    default: return SyncMode::FreeRun;
  }
}

}  // namespace

SyncSettings rewrite_from_dc_activation(const SyncRules& rules, SyncSettings s) {
  if (!rules.spec.sync_types_follow_dc_activation) return s;
  const auto dc = static_cast<std::uint16_t>(SyncType::DcSync0);
  const auto free_run = static_cast<std::uint16_t>(SyncType::FreeRun);
  if (dc_on(s)) {
    // L7750-L7780: 00h/01h/02h -> 02h (1C33h: 00h/22h/02h -> 02h).
    if (s.output_sync_type <= dc) s.output_sync_type = dc;
    if (s.input_sync_type == free_run || s.input_sync_type == rules.spec.input_sm2_sync_type ||
        s.input_sync_type == dc)
      s.input_sync_type = dc;
  } else {
    if (s.output_sync_type == dc) s.output_sync_type = free_run;
    if (s.input_sync_type == dc) s.input_sync_type = free_run;
  }
  return s;
}

SyncDecision check_sync_settings(const SyncRules& rules, const profile::AlStatusCodes& codes,
                                 const SyncSettings& s) {
  const profile::SyncSpec& spec = rules.spec;
  SyncDecision d;
  d.mode = mode_of(s.output_sync_type);
  auto refuse = [&d](std::uint16_t code) {
    d.result = {code, ecat::AlState::PreOp};
    return d;
  };

  // Sync types (A6B Err81.6, DS5C1 E-816): values the product accepts, a mode it runs, and without
  // DC both objects agree on SM2 synchronisation.
  if (!accepted(spec.sm2.accepted_sync_types, s.output_sync_type) ||
      !accepted(spec.sm3.accepted_sync_types, s.input_sync_type) || !mode_supported(spec, d.mode))
    return refuse(codes.sync_mode_not_supported);
  const bool output_sm2 = s.output_sync_type == static_cast<std::uint16_t>(SyncType::Sm2Event);
  const bool input_sm2 = s.input_sync_type == rules.spec.input_sm2_sync_type;
  if ((s.dc_activation & kDcActivationMask) == 0 && output_sm2 != input_sm2)
    return refuse(codes.sync_mode_not_supported);

  // DC activation (A6B Err81.5, DS5C1 E-815): bits 2-0 one of the accepted patterns.
  const std::uint8_t activation = s.dc_activation & kDcActivationMask;
  if (std::find(spec.accepted_dc_activation.begin(), spec.accepted_dc_activation.end(), activation) ==
      spec.accepted_dc_activation.end())
    return refuse(codes.invalid_dc_sync_config);

  // Cycle time (A6B Err81.0, DS5C1 E-810).
  switch (d.mode) {
    case SyncMode::DcSync0:
      if (!cycle_time_accepted(spec, s.sync0_cycle_ns)) return refuse(codes.invalid_sync_cycle_time);
      if (spec.sm2.cycle_time_writable) {
        if (!cycle_time_accepted(spec, s.cycle_time_ns)) return refuse(codes.invalid_sync_cycle_time);
        if (spec.cycle_must_equal_sync0 && s.cycle_time_ns != s.sync0_cycle_ns)
          return refuse(codes.invalid_sync_cycle_time);
      }
      d.cycle_ns = s.sync0_cycle_ns;
      break;
    case SyncMode::Sm2Event:
      // A read-only 1C32h-02h (DS1000A) is not the master's setting: the drive measures the
      // SM2 interval and checks it when it locks.
      if (spec.sm2.cycle_time_writable) {
        if (!cycle_time_accepted(spec, s.cycle_time_ns)) return refuse(codes.invalid_sync_cycle_time);
        d.cycle_ns = s.cycle_time_ns;
      }
      break;
    case SyncMode::FreeRun:
      d.cycle_ns = s.cycle_time_ns;   // the local event interval; may be 0 (A6B L7790)
      break;
  }
  return d;
}

}  // namespace vdrive::firmware::sync
