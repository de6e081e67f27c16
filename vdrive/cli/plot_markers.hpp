#pragma once
// What `vdrive plot` marks on the time axis: AL state changes and alarms (603Fh) a trace shows
// slave by slave (its `al_state` and `error_code` columns), and the events of an event log
// (`vdrive telemetry --events-csv`, the web page's events.csv: columns time_ns, slave, kind,
// text, found by name; text may be quoted with "" inside).
#include <string>
#include <vector>

#include "vdrive/cli/trace_csv.hpp"

namespace vdrive::cli {

struct PlotMarker {
  enum class Kind { al_state, alarm, fault, other };
  double time_s = 0.0;
  int slave = 0;  // 0: the line
  Kind kind = Kind::other;
  std::string text;  // short: "S2 Op", "S1 alarm 7380h", "S2 overload"
};

// Changes between consecutive rows of each slave (the first row is not a change).
std::vector<PlotMarker> trace_markers(const std::vector<const SlaveSeries*>& series);

// Sorted by time, markers of one kind at one instant (every slave reaching Op in one frame) made one,
// their texts joined: "S1 Op, S2 Op".
std::vector<PlotMarker> merge_simultaneous(std::vector<PlotMarker> markers);

// Throws TraceCsvError ("FILE:LINE: what") for a file that cannot be read or lacks time_ns, slave,
// kind or text.
std::vector<PlotMarker> read_event_markers(const std::string& path);

}  // namespace vdrive::cli
