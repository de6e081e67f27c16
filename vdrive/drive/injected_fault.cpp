#include "vdrive/drive/injected_fault.hpp"

#include <array>

namespace vdrive::drive {
namespace {

constexpr std::array<std::string_view, kInjectedFaultCount> kNames{
    "encoder_error",    "over_voltage",    "under_voltage", "main_power_off",
    "over_temperature", "following_error", "overload"};

}  // namespace

std::optional<InjectedFault> injected_fault_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return static_cast<InjectedFault>(i);
  return std::nullopt;
}

std::string_view name(InjectedFault fault) {
  const auto i = fault_index(fault);
  return i < kNames.size() ? kNames[i] : std::string_view("?");
}

const std::string& alarm_code_for(const profile::DriveAlarmCauses& c, InjectedFault fault) {
  switch (fault) {
    case InjectedFault::encoder_error: return c.encoder_error;
    case InjectedFault::over_voltage: return c.overvoltage;
    case InjectedFault::under_voltage: return c.undervoltage;
    case InjectedFault::main_power_off: return c.main_power_off;
    case InjectedFault::over_temperature: return c.overtemperature;
    case InjectedFault::following_error: return c.following_error;
    case InjectedFault::overload: return c.overload;
  }
  static const std::string none;
  return none;
}

}  // namespace vdrive::drive
