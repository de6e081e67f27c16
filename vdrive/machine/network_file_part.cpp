#include "vdrive/machine/network_file_part.hpp"

#include <fmt/core.h>

#include <optional>
#include <string>

#include "common/number_text.hpp"

namespace vdrive::machine {
namespace {

std::string describe_part(std::span<const network::LinePart> parts, std::size_t k) {
  const network::LinePart& p = parts[k];
  return p.count == 1 ? fmt::format("part {}, slave {}", k + 1, p.first + 1)
                      : fmt::format("part {}, slaves {}-{}", k + 1, p.first + 1, p.first + p.count);
}

// The first slave whose uplink makes the topology more than a line (each slave on port 1 of the one
// before, the first on the master), or none.
std::optional<std::size_t> first_branch(const network::Topology& t) {
  for (std::size_t i = 0; i < t.uplinks.size(); ++i) {
    const network::Uplink& up = t.uplinks[i];
    if (i == 0 ? up.parent != network::Uplink::kMaster : (up.parent != static_cast<int>(i - 1) || up.port != 1)) return i;
  }
  return std::nullopt;
}

}  // namespace

void check_cut(const NetworkFile& file, std::span<const network::LinePart> parts) {
  if (parts.size() <= 1) return;
  if (const std::optional<std::size_t> i = first_branch(file.topology)) {
    const network::Uplink& up = file.topology.uplinks[*i];
    const std::string on = up.parent == network::Uplink::kMaster
                               ? std::string("the master")
                               : fmt::format("port {} of slave {} ({})", up.port, up.parent + 1,
                                             file.slaves[static_cast<std::size_t>(up.parent)].name);
    throw NetworkFileError(fmt::format("{}:{}: slave {} ({}) is cabled to {}: the slaves form a tree; --processes "
                                       "cuts a line, so a tree is served in one process",
                                       file.file, file.slaves[*i].line, *i + 1, file.slaves[*i].name, on));
  }
  // In one process a slave's name wins over a position in a signal point ("3.home"); part 1's
  // router reads a number as a whole-line position, and a later part would read it as one of its own.
  for (std::size_t i = 0; i < file.slaves.size(); ++i) {
    if (parse_unsigned(file.slaves[i].name))
      throw NetworkFileError(fmt::format("{}:{}: slave {} is named '{}', a number: over --processes a number in a signal "
                                         "point is a whole-line position, so the name would not reach it; give it a "
                                         "name that is not a number",
                                         file.file, file.slaves[i].line, i + 1, file.slaves[i].name));
  }
  for (const network::SignalWire& w : file.wires) {
    const std::size_t from = network::part_of(parts, w.from.slave), to = network::part_of(parts, w.to.slave);
    if (from != to)
      throw NetworkFileError(fmt::format("{}: joins slave {} ({}) and slave {} ({}); a wire is copied inside one "
                                         "process, so --processes must keep both ends in one part",
                                         w.name, w.from.slave + 1, describe_part(parts, from), w.to.slave + 1,
                                         describe_part(parts, to)));
  }
  for (const ArmedFault& a : file.faults) {
    if (a.spec.station != 0)
      throw NetworkFileError(fmt::format("{}: a fault by station address cannot be given to one part of --processes "
                                         "(the master sets the addresses when it runs); name the slave or give its position",
                                         a.origin));
  }
}

NetworkFile line_part(const NetworkFile& file, network::LinePart p) {
  const auto inside = [&](std::size_t slave) { return slave >= p.first && slave < p.first + p.count; };
  NetworkFile out;
  out.file = file.file;
  out.slaves.assign(file.slaves.begin() + static_cast<long>(p.first),
                    file.slaves.begin() + static_cast<long>(p.first + p.count));
  for (network::SignalWire w : file.wires) {
    if (!inside(w.from.slave)) continue;
    w.from.slave -= p.first;
    w.to.slave -= p.first;
    out.wires.push_back(std::move(w));
  }
  for (network::NamedSignal s : file.signals) {
    if (!inside(s.point.slave)) continue;
    s.point.slave -= p.first;
    out.signals.push_back(std::move(s));
  }
  for (ArmedFault a : file.faults) {
    const bool at_slave = fault::acts_at_slave(a.spec.kind);
    // The master's wire reaches the part whose first slave is the line's first.
    if (at_slave ? !inside(static_cast<std::size_t>(a.spec.slave - 1)) : p.first != 0) continue;
    if (at_slave) a.spec.slave -= static_cast<int>(p.first);
    out.faults.push_back(std::move(a));
  }
  return out;
}

}  // namespace vdrive::machine
#include "common/number_text.hpp"
