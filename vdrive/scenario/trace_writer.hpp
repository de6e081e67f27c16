#pragma once
// The scenario trace: one CSV row per slave and trace period, with the drive's own values (AL
// state and status code from its ESC, 6041h, 6040h, 6061h, 6064h, 606Ch, 6077h, 60F4h, 603Fh, and
// the station address the master set, 0x0000 before it set one).
// Integers only, so the same scenario and seed give a byte-identical file.
#include <cstdint>
#include <fstream>
#include <string>

#include "common/clock.hpp"

namespace vdrive::scenario {

struct TraceRow {
  Nanos time = 0;
  int slave = 0;
  std::uint16_t al_status = 0, al_status_code = 0;
  std::uint16_t statusword = 0, controlword = 0;
  std::int64_t mode = 0, position = 0, velocity = 0, torque = 0, following_error = 0;
  std::uint16_t error_code = 0;
  std::uint16_t station = 0;
};

class TraceWriter {
public:
  static constexpr const char* kHeader =
      "time_ns,slave,al_state,al_status_code,statusword,controlword,mode,position,velocity,torque,following_error,error_code,station";

  // Throws std::runtime_error naming the file if it cannot be created.
  explicit TraceWriter(const std::string& path);
  void write(const TraceRow& row);

private:
  std::ofstream out_;
  std::string path_;
};

}  // namespace vdrive::scenario
