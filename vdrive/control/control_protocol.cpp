// JSON lines of the runtime control protocol. See control_protocol.hpp.
#include "vdrive/control/control_protocol.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "vdrive/fault/fault_fields.hpp"
#include "common/time_text.hpp"

namespace vdrive::control {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& message) { throw ProtocolError(message); }

std::string field(std::string_view name) { return fmt::format("fault field \"{}\"", name); }

double real(const json& v, std::string_view name) {
  if (!v.is_number()) fail(fmt::format("{}: expected a number, got {}", field(name), v.dump()));
  return v.get<double>();
}

std::int64_t integer(const json& v, std::string_view name, std::int64_t min, std::int64_t max) {
  std::int64_t x = 0;
  if (v.is_number_integer()) {
    x = v.get<std::int64_t>();
  } else if (v.is_string()) {  // "0x06020000": JSON has no hex numbers
    const std::string s = v.get<std::string>();
    std::size_t used = 0;
    try {
      x = std::stoll(s, &used, 0);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != s.size()) fail(fmt::format("{}: \"{}\" is not an integer", field(name), s));
  } else {
    fail(fmt::format("{}: expected an integer, got {}", field(name), v.dump()));
  }
  if (x < min || x > max) fail(fmt::format("{}: {} is out of range ({}..{})", field(name), x, min, max));
  return x;
}

std::string text(const json& v, std::string_view name) {
  if (!v.is_string()) fail(fmt::format("{}: expected a string, got {}", field(name), v.dump()));
  return v.get<std::string>();
}

Nanos time(const json& v, std::string_view name) {
  const std::string t = text(v, name);
  const std::optional<Nanos> ns = parse_time(t);
  if (!ns) fail(fmt::format("{}: \"{}\" is not a time with a unit (e.g. \"250ms\", \"1.5s\")", field(name), t));
  return *ns;
}

// A request's "fault" object as fault::read_fault asks for it. JSON has no position to point
// at, so a value that breaks a rule is quoted; the fields read are remembered so the rest can
// be refused as not applying to the kind.
class JsonFaultSource final : public fault::FaultFieldSource {
public:
  explicit JsonFaultSource(const json& j) : j_(j) {}
  bool has(std::string_view f) const override { return j_.contains(f); }
  std::string text(std::string_view f) override { return vdrive::control::text(at(f), f); }
  double real(std::string_view f) override { return vdrive::control::real(at(f), f); }
  std::int64_t integer(std::string_view f, std::int64_t min, std::int64_t max) override {
    return vdrive::control::integer(at(f), f, min, max);
  }
  Nanos time(std::string_view f) override { return vdrive::control::time(at(f), f); }
  std::optional<std::string> address_text(std::string_view f) override {
    if (!j_.contains(f) || !j_.at(std::string(f)).is_string()) return std::nullopt;
    return at(f).get<std::string>();
  }
  [[noreturn]] void missing(std::string_view f, std::string_view why) override {
    fail(fmt::format("{} is missing: {}", field(f), why));
  }
  [[noreturn]] void invalid(std::string_view f, std::string_view what) override { fail(fmt::format("{}: {}", field(f), what)); }
  [[noreturn]] void out_of_range(std::string_view f, std::string_view rule) override {
    fail(fmt::format("{}: {} {}", field(f), j_.at(std::string(f)).dump(), rule));
  }
  bool read(const std::string& f) const { return read_.contains(f); }

private:
  const json& at(std::string_view f) {
    read_.insert(std::string(f));
    return j_.at(std::string(f));
  }
  const json& j_;
  std::set<std::string, std::less<>> read_;
};

fault::FaultSpec fault_of(const json& j) {
  if (!j.is_object()) fail("\"fault\" must be an object");
  JsonFaultSource source(j);
  const fault::FaultSpec f = fault::read_fault(source, 65535);  // the injector checks the line's size
  for (const auto& [key, value] : j.items()) {
    if (!source.read(key)) fail(fmt::format("{} does not apply to kind \"{}\"", field(key), fault::info(f.kind).name));
  }
  return f;
}

std::string_view status_name(ControlReply::Status s) {
  switch (s) {
    case ControlReply::Status::ok: return "ok";
    case ControlReply::Status::bad_request: return "bad_request";
    case ControlReply::Status::denied: return "denied";
    case ControlReply::Status::failed: break;
  }
  return "failed";
}

}  // namespace

ControlRequest parse_request(std::string_view line) {
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number too large for a double
    fail(fmt::format("not a JSON request: {}", e.what()));
  }
  if (!j.is_object()) fail("a request is a JSON object with an \"op\"");
  constexpr std::string_view kOps = "inject, clear, clear_all, list, signal_get, signal_set, signals, find_station, line_status";
  if (!j.contains("op") || !j.at("op").is_string()) fail(fmt::format("\"op\" is missing ({})", kOps));
  const std::string op = j.at("op").get<std::string>();
  const std::set<std::string> allowed = op == "inject"       ? std::set<std::string>{"op", "fault"}
                                        : op == "clear"      ? std::set<std::string>{"op", "id"}
                                        : op == "signal_get" ? std::set<std::string>{"op", "signal"}
                                        : op == "signal_set" ? std::set<std::string>{"op", "signal", "value"}
                                        : op == "find_station" ? std::set<std::string>{"op", "station"}
                                                             : std::set<std::string>{"op"};
  ControlRequest r;
  if (op == "inject") r.op = ControlRequest::Op::inject;
  else if (op == "clear") r.op = ControlRequest::Op::clear;
  else if (op == "clear_all") r.op = ControlRequest::Op::clear_all;
  else if (op == "list") r.op = ControlRequest::Op::list;
  else if (op == "signal_get") r.op = ControlRequest::Op::signal_get;
  else if (op == "signal_set") r.op = ControlRequest::Op::signal_set;
  else if (op == "signals") r.op = ControlRequest::Op::signals;
  else if (op == "find_station") r.op = ControlRequest::Op::find_station;
  else if (op == "line_status") r.op = ControlRequest::Op::line_status;
  else fail(fmt::format("unknown op \"{}\" ({})", op, kOps));
  for (const auto& [key, value] : j.items()) {
    if (!allowed.contains(key)) fail(fmt::format("\"{}\" does not belong in a \"{}\" request", key, op));
  }
  if (r.op == ControlRequest::Op::inject) {
    if (!j.contains("fault")) fail("\"fault\" is missing from the inject request");
    r.fault = fault_of(j.at("fault"));
  } else if (r.op == ControlRequest::Op::clear) {
    if (!j.contains("id") || !j.at("id").is_number_integer() || j.at("id").get<std::int64_t>() < 1 ||
        j.at("id").get<std::int64_t>() > std::numeric_limits<int>::max())
      fail("\"id\" must be the id of an active fault (an integer from 1)");
    r.id = j.at("id").get<int>();
  } else if (r.op == ControlRequest::Op::find_station) {
    if (!j.contains("station")) fail("\"station\" is missing from the find_station request");
    try {
      r.station = static_cast<std::uint16_t>(integer(j.at("station"), "station", 1, 0xFFFF));
    } catch (const ProtocolError&) {
      fail(fmt::format("\"station\": expected a station address 0x0001..0xFFFF, got {}", j.at("station").dump()));
    }
  } else if (r.op == ControlRequest::Op::signal_get || r.op == ControlRequest::Op::signal_set) {
    if (!j.contains("signal") || !j.at("signal").is_string() || j.at("signal").get<std::string>().empty())
      fail("\"signal\" must name a signal of the network file or a point (\"di 0x6000:1\", \"x.home\")");
    r.signal = j.at("signal").get<std::string>();
    if (r.op == ControlRequest::Op::signal_set) {
      if (!j.contains("value")) fail("\"value\" is missing from the signal_set request");
      const json& v = j.at("value");
      if (v.is_boolean()) r.value = v.get<bool>() ? 1 : 0;
      else if (v.is_number_integer()) r.value = v.get<std::int64_t>();
      else fail(fmt::format("\"value\": expected an integer or true/false, got {}", v.dump()));
    }
  }
  return r;
}

std::string format_reply(const ControlReply& reply) {
  json j;
  j["ok"] = reply.ok();
  if (!reply.ok()) {
    j["status"] = status_name(reply.status);
    j["error"] = reply.error;
    return j.dump(-1, ' ', false, json::error_handler_t::replace);  // a message may quote bad bytes
  }
  if (reply.id != 0) j["id"] = reply.id;
  j["cleared"] = reply.cleared;
  if (reply.slave != 0) j["slave"] = reply.slave;
  json faults = json::array();
  for (const FaultStatus& f : reply.faults) {
    json o{{"id", f.id}, {"kind", f.kind}, {"description", f.description}, {"elapsed_ns", f.elapsed}};
    o["remaining_ns"] = f.remaining < 0 ? json(nullptr) : json(f.remaining);
    faults.push_back(std::move(o));
  }
  j["faults"] = std::move(faults);
  if (!reply.states.empty()) {
    json states = json::array();
    for (const SlaveState& st : reply.states)
      states.push_back({{"al_status", st.al_status}, {"al_status_code", st.al_status_code}, {"rx_errors", st.rx_errors}});
    j["states"] = std::move(states);
  }
  if (!reply.signals.empty()) {
    json signals = json::array();
    for (const SignalStatus& s : reply.signals)
      signals.push_back({{"name", s.name}, {"point", s.point}, {"type", s.type}, {"value", s.value}});
    j["signals"] = std::move(signals);
  }
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

ControlReply parse_reply(std::string_view line) {
  try {
    const json j = json::parse(line);
    ControlReply r;
    if (!j.at("ok").get<bool>()) {
      const std::string s = j.value("status", "failed");
      r.status = s == "bad_request" ? ControlReply::Status::bad_request
                 : s == "denied"    ? ControlReply::Status::denied
                                    : ControlReply::Status::failed;
      r.error = j.value("error", "no reason given");
      return r;
    }
    r.id = j.value("id", 0);
    r.cleared = j.value("cleared", 0);
    r.slave = j.value("slave", 0);
    for (const json& f : j.value("faults", json::array())) {
      const json& rem = f.at("remaining_ns");
      r.faults.push_back({f.at("id").get<int>(), f.at("kind").get<std::string>(), f.at("description").get<std::string>(),
                          f.at("elapsed_ns").get<Nanos>(), rem.is_null() ? Nanos{-1} : rem.get<Nanos>()});
    }
    for (const json& st : j.value("states", json::array()))
      r.states.push_back({st.at("al_status").get<std::uint16_t>(), st.at("al_status_code").get<std::uint16_t>(),
                          st.at("rx_errors").get<std::uint32_t>()});
    for (const json& s : j.value("signals", json::array())) {
      r.signals.push_back({s.at("name").get<std::string>(), s.at("point").get<std::string>(),
                           s.at("type").get<std::string>(), s.at("value").get<std::int64_t>()});
    }
    return r;
  } catch (const json::exception& e) {
    throw ProtocolError(fmt::format("garbled reply from vdrive: {}", e.what()));
  }
}

}  // namespace vdrive::control
