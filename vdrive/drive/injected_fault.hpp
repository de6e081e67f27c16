#pragma once
// Causes a fault injector can switch on and off on a drive: each stands for a condition
// the real drive detects (a lost encoder, a bus voltage out of range, ...). While one is active its
// cause is present: the product's alarm for it (profile.drive.alarms) is raised and cannot be
// cleared; once it is inactive the product's own clearing procedure applies. The engine side is
// DriveEngine::set_injected_fault (drive_engine.hpp).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::drive {

enum class InjectedFault : std::uint8_t {
  encoder_error,     // encoder communication lost
  over_voltage,      // DC bus over-voltage
  under_voltage,     // DC bus under-voltage (also takes the main power away)
  main_power_off,    // main (power-stage) supply switched off: 6041h bit 4 drops
  over_temperature,  // drive or motor over-temperature (raised directly, not through the winding model)
  following_error,   // position deviation beyond the product's level
  overload,          // the product's overload detection trips
};

inline constexpr std::size_t kInjectedFaultCount = 7;

// "encoder_error", "over_voltage", ... (the enumerator's name); nullopt for anything else.
std::optional<InjectedFault> injected_fault_from_name(std::string_view name);
std::string_view name(InjectedFault fault);

// The product's alarm code for the fault ("" = the product has none).
const std::string& alarm_code_for(const profile::DriveAlarmCauses& causes, InjectedFault fault);

// The fault removes the main power (PDS main-power input, 6041h bit 4).
constexpr bool removes_main_power(InjectedFault f) {
  return f == InjectedFault::main_power_off || f == InjectedFault::under_voltage;
}

constexpr std::size_t fault_index(InjectedFault f) { return static_cast<std::size_t>(f); }
static_assert(fault_index(InjectedFault::overload) + 1 == kInjectedFaultCount, "one count per enumerator");

}  // namespace vdrive::drive
