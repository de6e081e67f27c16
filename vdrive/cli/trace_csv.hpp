#pragma once
// A trace CSV as `vdrive plot` reads it: the scenario trace (vdrive/scenario/trace_writer.hpp) or
// the telemetry CSV. Columns are found by their header name, not their position, so both read
// alike: time (`time_ns`, or `time_s`), `slave`, `position`, `velocity`, `torque`,
// `following_error`, and where present `al_state` and `error_code` (603Fh), which mark AL changes
// and alarms on the plot, and `station` (the station address, for --slave 0x1002 and the legend);
// other columns are ignored. Rows come back grouped per slave, in file order.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace vdrive::cli {

struct SlaveSeries {
  int slave = 0;
  std::uint16_t station = 0;  // the last station address in its rows (0: none, or no such column)
  std::vector<double> time_s, position, velocity, torque, following_error;
  std::vector<double> al_state, error_code;  // empty when the trace has no such column
};

struct TraceCsv {
  std::vector<SlaveSeries> slaves;  // ascending slave number
};

// "FILE: what" or "FILE:LINE: what": a missing file, no header, a missing column, a value that
// is not a number, no rows.
class TraceCsvError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

TraceCsv read_trace_csv(const std::string& path);

}  // namespace vdrive::cli
