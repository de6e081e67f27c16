#include "vdrive/scenario/trace_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>

namespace vdrive::scenario {

TraceWriter::TraceWriter(const std::string& path) : out_(path, std::ios::trunc), path_(path) {
  if (!out_) throw std::runtime_error(path + ": cannot create the trace file");
  out_ << kHeader << '\n';
}

void TraceWriter::write(const TraceRow& r) {
  out_ << fmt::format("{},{},{},0x{:04X},0x{:04X},0x{:04X},{},{},{},{},{},0x{:04X},0x{:04X}\n", r.time, r.slave, r.al_status & 0x0F,
                      r.al_status_code, r.statusword, r.controlword, r.mode, r.position, r.velocity, r.torque,
                      r.following_error, r.error_code, r.station);
  if (!out_) throw std::runtime_error(path_ + ": writing the trace failed");
}

}  // namespace vdrive::scenario
