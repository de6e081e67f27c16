#pragma once
// What the event loop hands the telemetry thread: fixed-size values (no strings, no heap), so
// copying one into the SPSC queue allocates nothing. The telemetry thread turns them into the
// DDS messages of idl/Telemetry.idl; fields and units are the same (docs/telemetry.md).
#include <array>
#include <cstdint>
#include <variant>

#include "common/clock.hpp"

namespace vdrive::telemetry {

struct AxisSample {
  Nanos time = 0;
  std::uint16_t slave = 0;  // from 1
  std::uint16_t station = 0;  // station address 0x0010 the master set (0: none yet)
  std::uint16_t al_state = 0, al_status_code = 0;
  std::uint16_t statusword = 0, controlword = 0;
  std::int8_t mode = 0;
  std::int32_t position = 0, velocity = 0;
  std::int16_t torque = 0;
  std::int32_t following_error = 0;
  std::uint16_t error_code = 0;
  // Not on the DDS topic (the web page plots and shows them): 607Ah, 60FDh, 60B9h, 60BAh; 0 where
  // the product has none.
  std::int32_t target_position = 0;
  std::uint32_t digital_inputs = 0;
  std::uint16_t probe_status = 0;
  std::int32_t probe_position1 = 0;
  double winding_c = 0.0, housing_c = 0.0;  // NaN without a plant
};

struct BusSample {
  Nanos time = 0;
  std::uint16_t slave = 0;
  std::uint16_t station = 0;
  std::uint16_t al_state = 0, al_status_code = 0;
  std::uint64_t frames_in = 0, frames_out = 0, frames_dropped = 0, send_failed = 0;
  std::uint32_t rx_errors = 0, lost_links = 0;
  std::uint64_t samples_dropped = 0;
  // Frame in to reply out over the sample period; all 0 when no frame came.
  Nanos turnaround_last = 0, turnaround_min = 0, turnaround_mean = 0, turnaround_max = 0;
  // Host stalls so far and the longest (runtime/host_stalls.hpp; the same in every slave's sample).
  std::uint64_t host_stalls = 0;
  Nanos longest_host_stall = 0;
};

enum class EventKind : std::uint8_t { al_state, alarm_raised, alarm_cleared, fault_injected, fault_cleared, plant_set, signal, host_stall };

struct EventSample {
  Nanos time = 0;
  std::uint16_t slave = 0;  // 0: the line
  EventKind kind = EventKind::al_state;
  std::uint32_t value = 0, previous = 0;
  std::array<char, 128> text{};  // NUL-terminated (a host stall's description is the longest)
};

using Sample = std::variant<AxisSample, BusSample, EventSample>;

// "al_state", "alarm_raised", ... as the Event_ message's `kind` carries them.
const char* event_kind_name(EventKind kind);

}  // namespace vdrive::telemetry
