#include "vdrive/fault/fault_spec.hpp"

#include <array>

#include <fmt/format.h>

#include "ethercat/slave_ref.hpp"

namespace vdrive::fault {
namespace {

using K = FaultKind;
using L = Layer;

constexpr std::array<FaultKindInfo, 26> kCatalogue{{
    {K::drop, "drop", L::wire, false, "frames lost on the wire (probability per frame)"},
    {K::corrupt, "corrupt", L::wire, false, "frames with a bad FCS: counted by the ESCs, never back to the master"},
    {K::duplicate, "duplicate", L::wire, false, "frames delivered twice"},
    {K::reorder, "reorder", L::wire, false, "a frame held back behind the next one"},
    {K::delay, "delay", L::wire, false, "every frame held for `delay`"},
    {K::link_down, "link_down", L::wire, false, "cable into slave N (or at its `port`) broken (links down on both sides), healed at the end"},
    {K::wkc_error, "wkc_error", L::esc, false, "the ESC executes nothing addressed to it: working counters fall short"},
    {K::sii_error, "sii_error", L::esc, false, "SII EEPROM reads fail with the EEPROM error bits"},
    {K::sync_lost, "sync_lost", L::esc, false, "the DC unit generates no SYNC0/SYNC1"},
    {K::watchdog, "watchdog", L::esc, false, "the process-data watchdog is expired"},
    {K::lost_reply, "lost_reply", L::mailbox, true, "the next `count` mailbox replies are lost"},
    {K::duplicate_reply, "duplicate_reply", L::mailbox, true, "the next `count` mailbox replies are sent twice"},
    {K::toggle_error, "toggle_error", L::mailbox, true, "the next SDO segment reply has the wrong toggle bit"},
    {K::sdo_abort, "sdo_abort", L::mailbox, true, "the next SDO request is aborted with `abort_code`"},
    {K::encoder_error, "encoder_error", L::drive, false, "encoder communication lost"},
    {K::overload, "overload", L::drive, false, "the drive's overload detection trips"},
    {K::over_voltage, "over_voltage", L::drive, false, "DC bus over-voltage"},
    {K::under_voltage, "under_voltage", L::drive, false, "DC bus under-voltage"},
    {K::main_power_off, "main_power_off", L::drive, false, "main power removed"},
    {K::over_temperature, "over_temperature", L::drive, false, "drive or motor over-temperature"},
    {K::following_error, "following_error", L::drive, false, "position deviation beyond the product's level"},
    {K::alarm, "alarm", L::drive, true, "any alarm of the product's table, by its code"},
    {K::jam, "jam", L::plant, false, "the load seizes where it is"},
    {K::collision, "collision", L::plant, false, "a hard obstacle appears at `position`"},
    {K::load_change, "load_change", L::plant, false, "load inertia times `load_scale`, plus `force`, friction times `friction_scale`"},
    {K::brake_failure, "brake_failure", L::plant, false, "the holding brake does not hold"},
}};

std::string_view direction_name(WireDirection d) {
  switch (d) {
    case WireDirection::both: return "both ways";
    case WireDirection::to_slaves: return "to the slaves";
    case WireDirection::to_master: return "to the master";
  }
  return "?";
}

}  // namespace

std::span<const FaultKindInfo> fault_catalogue() { return kCatalogue; }

const FaultKindInfo& info(FaultKind kind) { return kCatalogue[static_cast<std::size_t>(kind)]; }

bool acts_at_slave(FaultKind kind) { return info(kind).layer != Layer::wire || kind == FaultKind::link_down; }

std::optional<FaultKind> fault_kind_from_name(std::string_view name) {
  for (const FaultKindInfo& i : kCatalogue)
    if (i.name == name) return i.kind;
  return std::nullopt;
}

std::string_view name(Layer layer) {
  switch (layer) {
    case Layer::wire: return "wire";
    case Layer::esc: return "esc";
    case Layer::mailbox: return "mailbox";
    case Layer::drive: return "drive";
    case Layer::plant: return "plant";
  }
  return "?";
}

std::string describe(const FaultSpec& s) {
  const FaultKindInfo& i = info(s.kind);
  std::string text(i.name);
  const std::string who = s.station != 0 && s.slave == 0 ? ecat::hex_address(s.station) : std::to_string(s.slave);
  switch (s.kind) {
    case K::drop: case K::corrupt: case K::duplicate: case K::reorder:
      text += fmt::format(" {} p={}", direction_name(s.direction), s.probability);
      break;
    case K::delay: text += fmt::format(" {} {} ns", direction_name(s.direction), s.delay); break;
    case K::link_down:
      text += s.port == 0 ? fmt::format(" cable into slave {}", who) : fmt::format(" cable at slave {} port {}", who, s.port);
      break;
    case K::lost_reply: case K::duplicate_reply: text += fmt::format(" slave {} x{}", who, s.count); break;
    case K::sdo_abort: text += fmt::format(" slave {} abort 0x{:08X}", who, s.abort_code); break;
    case K::alarm: text += fmt::format(" slave {} code {}", who, s.alarm); break;
    case K::collision: text += fmt::format(" slave {} at {}", who, s.position); break;
    case K::load_change:
      text += fmt::format(" slave {} x{} +{}", who, s.load_scale, s.force);
      if (s.friction_scale != 1.0) text += fmt::format(" friction x{}", s.friction_scale);
      break;
    default: text += fmt::format(" slave {}", who); break;
  }
  if (!i.one_shot && s.duration > 0) text += fmt::format(" for {} us", s.duration / 1000);
  return text;
}

}  // namespace vdrive::fault
