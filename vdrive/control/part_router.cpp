// Part 1's control socket routing requests over the parts of `vdrive run --processes`. See
// part_router.hpp.
#include "vdrive/control/part_router.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <cctype>
#include <optional>
#include <nlohmann/json.hpp>

#include "common/number_text.hpp"
#include "ethercat/slave_ref.hpp"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/control_socket.hpp"
#include "vdrive/control/run_fault_id.hpp"
#include "vdrive/network/line_parts.hpp"
#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::control {
namespace {

using nlohmann::json;
using Status = ControlReply::Status;

std::string op_line(std::string_view op) { return json{{"op", op}}.dump(); }

// find_slave's "(the line has 0x1001, 0x1002)" is one part's addresses, not the line's.
std::string part_says(std::string name, const std::string& error) {
  std::string text = error;
  if (const std::size_t at = text.find("(the line has "); at != std::string::npos) text.replace(at, 14, "(it has ");
  return name + ": " + text;
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The slave of a point as network::parse_signal_point splits it ("3 0x6010:1" -> "3", "x.home" ->
// "x"), or empty for a named signal (a signal's name has neither ' ' nor '.').
std::string_view point_slave(std::string_view point) {
  std::size_t at = point.find_last_of(' ');
  if (at == std::string_view::npos) at = point.find_last_of('.');
  return at == std::string_view::npos ? std::string_view{} : point.substr(0, at);
}

// A point whose slave is a position (as a part without slave names formats it) moved by `offset`;
// a named slave (a network file's "x", or its "slave 3" for an unnamed one) is the same in every part.
std::string shift_point(const std::string& point, std::size_t offset) {
  const std::string_view slave = point_slave(point);
  const std::optional<std::uint64_t> position = parse_unsigned(slave);
  if (!position) return point;
  return std::to_string(*position + offset) + point.substr(slave.size());
}

// How network::named_or_parsed_point refuses a text that is no signal of that part: for a named
// signal any such refusal, for a point only when the part has no slave of that name (a slave it
// has, with an entry that does not parse, is the user's mistake, not another part's slave).
bool lacks_signal(const ControlReply& reply, const std::string& signal) {
  if (reply.status != Status::bad_request || !reply.error.starts_with(fmt::format("no signal '{}' (", signal))) return false;
  const std::string_view slave = point_slave(signal);
  return slave.empty() || reply.error.find(fmt::format(": '{}': no slave '{}' (", signal, slave)) != std::string::npos;
}

// "mode, y_home" from a refusal's "(signals: mode, y_home)", "none" from "(the network names none)".
std::string signals_listed(const std::string& refusal, const std::string& signal) {
  const std::size_t from = fmt::format("no signal '{}' (", signal).size();
  const std::size_t to = refusal.find(") and not a point: ", from);
  if (to == std::string::npos) return refusal;
  const std::string_view listed = std::string_view(refusal).substr(from, to - from);
  return listed.starts_with("signals: ") ? std::string(listed.substr(9)) : "none";
}

}  // namespace

std::string shift_slave_numbers(std::string_view text, std::size_t offset) {
  constexpr std::string_view kWord = "slave ";
  std::string out;
  out.reserve(text.size() + 8);
  std::size_t at = 0;
  for (;;) {
    const std::size_t found = text.find(kWord, at);
    if (found == std::string_view::npos) break;
    std::size_t digits = found + kWord.size();
    out.append(text.substr(at, digits - at));
    // "'slave 3'" is a name as given (a network file's name for its unnamed third slave), not a position.
    if (found > 0 && text[found - 1] == '\'') {
      at = digits;
      continue;
    }
    std::size_t end = digits;
    while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end])) != 0) ++end;
    // "slave 0x1003" is an address, the same in every part; "slave 12" a position here.
    const bool address = end == digits + 1 && text[digits] == '0' && end < text.size() && (text[end] == 'x' || text[end] == 'X');
    if (end == digits || address || end - digits > 9) {
      at = digits;
      continue;
    }
    out += std::to_string(std::stoul(std::string(text.substr(digits, end - digits))) + offset);
    at = end;
  }
  out.append(text.substr(at));
  return out;
}

PartRouter::PartRouter(std::size_t own_slaves, std::vector<RemotePart> later, Local local, Call call, Nanos timeout)
    : own_slaves_(own_slaves), later_(std::move(later)), local_(std::move(local)), call_(std::move(call)), timeout_(timeout) {}

std::string PartRouter::part_name(std::size_t part) const {
  const std::size_t first = first_of(part);
  const std::size_t count = part == 0 ? own_slaves_ : later_[part - 1].count;
  return network::part_name(part, {first, count});
}

std::string PartRouter::answer(std::string_view line) {
  ControlReply reply;
  try {
    reply = route(parse_request(line), line);
  } catch (const ProtocolError& e) {
    reply = error_reply(Status::bad_request, e.what());
  }
  if (!reply.ok()) spdlog::warn("control request refused: {}", reply.error);
  return format_reply(reply);
}

ControlReply PartRouter::route(const ControlRequest& r, std::string_view line) {
  switch (r.op) {
    case ControlRequest::Op::inject: return inject(r, line);
    case ControlRequest::Op::clear: return clear(r);
    case ControlRequest::Op::clear_all:
    case ControlRequest::Op::list: return fan_out(r);
    case ControlRequest::Op::find_station: return find_station(r, line);
    case ControlRequest::Op::signals: return list_signals(r);
    case ControlRequest::Op::signal_get:
    case ControlRequest::Op::signal_set: return signal(r, line);
    case ControlRequest::Op::line_status: return line_states(r);
  }
  return local_(r);
}

std::size_t PartRouter::line_slaves() const {
  return later_.empty() ? own_slaves_ : later_.back().first + later_.back().count;
}

std::size_t PartRouter::part_at(std::size_t position) const {
  for (std::size_t k = 1; k < parts(); ++k) {
    const RemotePart& p = later_[k - 1];
    if (position > p.first && position <= p.first + p.count) return k;
  }
  return 0;
}

ControlReply PartRouter::inject(const ControlRequest& r, std::string_view line) {
  const fault::FaultSpec& s = r.fault;
  const bool at_a_slave = fault::acts_at_slave(s.kind);
  if (at_a_slave && s.slave == 0 && s.station != 0) return inject_at_station(r, line);
  const std::size_t part = at_a_slave && s.slave > 0 ? part_at(static_cast<std::size_t>(s.slave)) : 0;
  // Wire faults act at part 1's port to the master, for the whole line; a position beyond the
  // line is refused here, where the injector knows the line's length (set_later_slaves).
  if (part == 0) {
    ControlReply reply = local_(r);
    reply.id = run_fault_id(0, reply.id, parts());
    return reply;
  }
  json j = json::parse(line);
  j["fault"]["slave"] = static_cast<std::size_t>(s.slave) - first_of(part);
  ControlReply reply = forward(part, j.dump());
  if (reply.ok())
    spdlog::info("fault {} injected in {}: {}", reply.id, part_name(part), fault::describe(s));
  return reply;
}

ControlReply PartRouter::inject_at_station(const ControlRequest& r, std::string_view line) {
  ControlRequest where;
  where.op = ControlRequest::Op::find_station;
  where.station = r.fault.station;
  ControlReply here = local_(where);
  if (here.ok()) {
    ControlReply reply = local_(r);
    reply.id = run_fault_id(0, reply.id, parts());
    return reply;
  }
  if (here.status != Status::bad_request) return here;
  std::vector<std::string> not_found{part_says(part_name(0), here.error)};
  std::vector<std::string> silent;
  const std::string ask = json{{"op", "find_station"}, {"station", ecat::hex_address(r.fault.station)}}.dump();
  for (std::size_t k = 1; k < parts(); ++k) {
    const ControlReply there = forward(k, ask);
    if (there.ok()) {
      // Forwarded as given: that part finds the address itself when the fault starts.
      ControlReply reply = forward(k, std::string(line));
      if (reply.ok()) spdlog::info("fault {} injected in {}: {}", reply.id, part_name(k), fault::describe(r.fault));
      return reply;
    }
    (there.status == Status::bad_request ? not_found : silent).push_back(there.status == Status::bad_request
                                                                            ? part_says(part_name(k), there.error)
                                                                            : there.error);
  }
  const std::string what = fmt::format("{}: no part of this run's line has station address {} ({})", fault::describe(r.fault),
                                       ecat::hex_address(r.fault.station), join(not_found));
  if (!silent.empty()) return error_reply(Status::failed, fmt::format("{}; {}", what, join(silent)));
  return error_reply(Status::bad_request, what);
}

ControlReply PartRouter::clear(const ControlRequest& r) {
  const PartFaultId at = part_fault_id(r.id, parts());
  ControlReply reply;
  if (at.part == 0) {
    ControlRequest own = r;
    own.id = at.id;
    reply = local_(own);
  } else {
    reply = forward(at.part, json{{"op", "clear"}, {"id", at.id}}.dump());
    if (reply.ok()) spdlog::info("fault {} cleared in {}", r.id, part_name(at.part));
  }
  // The part's refusal names its own id; the user gave the run-wide one.
  if (reply.status == Status::bad_request) return error_reply(Status::bad_request, fmt::format("no active fault {}", r.id));
  return reply;
}

ControlReply PartRouter::fan_out(const ControlRequest& r) {
  ControlReply merged = local_(r);
  if (!merged.ok()) return merged;
  for (FaultStatus& f : merged.faults) f.id = run_fault_id(0, f.id, parts());
  std::vector<std::string> silent;
  const std::string ask = r.op == ControlRequest::Op::list ? op_line("list") : op_line("clear_all");
  for (std::size_t k = 1; k < parts(); ++k) {
    ControlReply there = forward(k, ask);
    if (!there.ok()) {
      silent.push_back(there.error);
      continue;
    }
    merged.cleared += there.cleared;
    for (FaultStatus& f : there.faults) merged.faults.push_back(std::move(f));
  }
  if (silent.empty()) return merged;
  // A part that does not answer is an error, but the user still learns what the others did.
  std::string done;
  if (r.op == ControlRequest::Op::clear_all) {
    done = fmt::format("{} fault(s) cleared in the other parts", merged.cleared);
  } else {
    std::vector<std::string> listed;
    for (const FaultStatus& f : merged.faults) listed.push_back(fmt::format("{} {}", f.id, f.description));
    done = listed.empty() ? "the other parts have no active faults"
                          : fmt::format("the other parts' active faults: {}", fmt::join(listed, ", "));
  }
  return error_reply(Status::failed, fmt::format("{}; {}", join(silent), done));
}

ControlReply PartRouter::line_states(const ControlRequest& r) {
  ControlReply merged = local_(r);
  if (!merged.ok()) return merged;
  for (std::size_t k = 1; k < parts(); ++k) {
    ControlReply there = forward(k, op_line("line_status"));
    if (!there.ok()) return there;
    for (const SlaveState& s : there.states) merged.states.push_back(s);
  }
  return merged;
}

ControlReply PartRouter::find_station(const ControlRequest& r, std::string_view line) {
  ControlReply here = local_(r);
  if (here.ok() || here.status != Status::bad_request) return here;
  std::vector<std::string> not_found{part_says(part_name(0), here.error)};
  for (std::size_t k = 1; k < parts(); ++k) {
    ControlReply there = forward(k, std::string(line));
    if (there.ok()) return there;
    not_found.push_back(there.status == Status::bad_request ? part_says(part_name(k), there.error) : there.error);
  }
  return error_reply(Status::bad_request, fmt::format("no part of this run's line has station address {} ({})",
                                                      ecat::hex_address(r.station), join(not_found)));
}

ControlReply PartRouter::list_signals(const ControlRequest& r) {
  ControlReply merged = local_(r);
  if (!merged.ok()) return merged;
  std::vector<std::string> silent;
  for (std::size_t k = 1; k < parts(); ++k) {
    ControlReply there = forward(k, op_line("signals"));
    if (!there.ok()) {
      silent.push_back(there.error);
      continue;
    }
    for (SignalStatus& s : there.signals) merged.signals.push_back(std::move(s));
  }
  if (silent.empty()) return merged;
  // As for faults: the part that does not answer is an error, and the user still learns the rest.
  std::vector<std::string> listed;
  for (const SignalStatus& s : merged.signals) listed.push_back(fmt::format("{} ({}) = {}", s.name, s.point, s.value));
  return error_reply(Status::failed, fmt::format("{}; {}", join(silent),
                                                 listed.empty() ? "the other parts name no signals"
                                                                : fmt::format("the other parts' signals: {}", fmt::join(listed, ", "))));
}

ControlReply PartRouter::signal(const ControlRequest& r, std::string_view line) {
  const std::optional<std::uint64_t> position = parse_unsigned(point_slave(r.signal));
  return position ? signal_at(r, line, *position) : signal_anywhere(r, line);
}

ControlReply PartRouter::signal_at(const ControlRequest& r, std::string_view line, std::uint64_t position) {
  // Part 1 would say "or a position 1-2", its own slaves; the user counts the whole line.
  if (position == 0 || position > line_slaves())
    return error_reply(Status::bad_request, fmt::format("'{}': no slave {} (this run's line has slaves 1-{})", r.signal,
                                                        position, line_slaves()));
  const std::size_t part = part_at(position);
  if (part == 0) return local_(r);
  const std::string local_point =
      std::to_string(position - first_of(part)) + r.signal.substr(point_slave(r.signal).size());
  json j = json::parse(line);
  j["signal"] = local_point;
  ControlReply reply = forward(part, j.dump());
  // The part names the point as it was asked of it; the user asked for the whole line's.
  for (SignalStatus& s : reply.signals) s.name = r.signal;
  reply.error = replace_all(reply.error, fmt::format("'{}'", local_point), fmt::format("'{}'", r.signal));
  return reply;
}

ControlReply PartRouter::signal_anywhere(const ControlRequest& r, std::string_view line) {
  const ControlReply here = local_(r);
  if (!lacks_signal(here, r.signal)) return here;
  std::vector<std::string> listed{fmt::format("{} has {}", part_name(0), signals_listed(here.error, r.signal))};
  std::vector<std::string> silent;
  for (std::size_t k = 1; k < parts(); ++k) {
    ControlReply there = forward(k, std::string(line));
    // Signal and slave names are the network file's, each in one part: the first that has it is the one.
    if (lacks_signal(there, r.signal)) listed.push_back(fmt::format("{} has {}", part_name(k), signals_listed(there.error, r.signal)));
    else if (there.status == Status::failed) silent.push_back(there.error);
    else return there;
  }
  const std::string_view slave = point_slave(r.signal);
  std::string what;
  if (slave.empty()) {
    // Part 1's reason why it is no point holds for every part: a text without ' ' or '.' never parses.
    const std::size_t tail = here.error.find(") and not a point: ");
    what = fmt::format("no part of this run's line has signal '{}' ({}){}", r.signal, join(listed),
                       tail == std::string::npos ? "" : here.error.substr(tail + 1));
  } else {
    what = fmt::format("'{}': no part of this run's line has a slave '{}' (name one of the network file's slaves, or "
                       "give a position 1-{})", r.signal, slave, line_slaves());
  }
  if (!silent.empty()) return error_reply(Status::failed, fmt::format("{}; {}", what, join(silent)));
  return error_reply(Status::bad_request, what);
}

ControlReply PartRouter::forward(std::size_t part, const std::string& line) {
  const RemotePart& p = later_[part - 1];
  ControlReply reply;
  try {
    reply = parse_reply(call_(p.socket, line, timeout_));
  } catch (const ControlSocketError& e) {
    return error_reply(Status::failed, fmt::format("{} does not answer (has it ended?): {}", part_name(part), e.what()));
  } catch (const ProtocolError& e) {
    return error_reply(Status::failed, fmt::format("{}: {}", part_name(part), e.what()));
  }
  if (!reply.ok()) {
    reply.error = shift_slave_numbers(reply.error, p.first);
    return reply;
  }
  reply.id = run_fault_id(part, reply.id, parts());
  if (reply.slave != 0) reply.slave += static_cast<int>(p.first);
  for (FaultStatus& f : reply.faults) {
    f.id = run_fault_id(part, f.id, parts());
    f.description = shift_slave_numbers(f.description, p.first);
  }
  for (SignalStatus& s : reply.signals) s.point = shift_point(s.point, p.first);
  return reply;
}

}  // namespace vdrive::control
