// JSON lines of the runtime control protocol. See control_protocol.hpp.
#include "vdrive/control/control_protocol.hpp"

#include <fmt/core.h>

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "vdrive/scenario/time_value.hpp"

namespace vdrive::control {
namespace {

using nlohmann::json;
using K = fault::FaultKind;

[[noreturn]] void fail(const std::string& message) { throw ProtocolError(message); }

std::string kind_names() {
  std::string names;
  for (const auto& i : fault::fault_catalogue()) names += (names.empty() ? "" : ", ") + std::string(i.name);
  return names;
}

// The fields a fault of `kind` takes, besides "kind" (as fault_of in scenario_loader.cpp).
std::set<std::string> fields_of(K kind) {
  const fault::FaultKindInfo& i = fault::info(kind);
  std::set<std::string> f;
  if (i.layer != fault::Layer::wire || kind == K::link_down) f.insert("slave");
  if (!i.one_shot) f.insert("duration");
  switch (kind) {
    case K::drop: case K::corrupt: case K::duplicate: case K::reorder: f.insert({"direction", "probability"}); break;
    case K::delay: f.insert({"direction", "delay"}); break;
    case K::lost_reply: case K::duplicate_reply: f.insert("count"); break;
    case K::sdo_abort: f.insert("abort_code"); break;
    case K::alarm: f.insert("code"); break;
    case K::collision: f.insert("position"); break;
    case K::load_change: f.insert({"load_scale", "force"}); break;
    default: break;
  }
  return f;
}

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
  const std::optional<Nanos> ns = scenario::parse_time(t);
  if (!ns) fail(fmt::format("{}: \"{}\" is not a time with a unit (e.g. \"250ms\", \"1.5s\")", field(name), t));
  return *ns;
}

fault::FaultSpec fault_of(const json& j) {
  if (!j.is_object()) fail("\"fault\" must be an object");
  if (!j.contains("kind")) fail(fmt::format("{} is missing (one of: {})", field("kind"), kind_names()));
  const std::string kind = text(j.at("kind"), "kind");
  const std::optional<K> k = fault::fault_kind_from_name(kind);
  if (!k) fail(fmt::format("unknown fault kind \"{}\" ({})", kind, kind_names()));
  fault::FaultSpec f;
  f.kind = *k;
  const std::set<std::string> allowed = fields_of(f.kind);
  for (const auto& [key, value] : j.items()) {
    if (key != "kind" && !allowed.contains(key)) fail(fmt::format("{} does not apply to kind \"{}\"", field(key), kind));
  }
  auto has = [&](const char* key) { return j.contains(key); };
  if (allowed.contains("slave")) {
    if (!has("slave")) fail(fmt::format("{} is missing: kind \"{}\" acts on one slave (1 = first)", field("slave"), kind));
    f.slave = static_cast<int>(integer(j.at("slave"), "slave", 1, 65535));
  }
  if (has("duration")) f.duration = time(j.at("duration"), "duration");
  if (has("direction")) {
    const std::string d = text(j.at("direction"), "direction");
    if (d == "both") f.direction = fault::WireDirection::both;
    else if (d == "to_slaves") f.direction = fault::WireDirection::to_slaves;
    else if (d == "to_master") f.direction = fault::WireDirection::to_master;
    else fail(fmt::format("{}: unknown direction \"{}\" (both, to_slaves, to_master)", field("direction"), d));
  }
  if (has("probability")) {
    f.probability = real(j.at("probability"), "probability");
    if (f.probability < 0.0 || f.probability > 1.0) fail(fmt::format("{}: {} must be between 0 and 1", field("probability"), f.probability));
  }
  if (f.kind == K::delay) {
    if (!has("delay")) fail(fmt::format("{} is missing: kind \"delay\" needs how long (e.g. \"2ms\")", field("delay")));
    f.delay = time(j.at("delay"), "delay");
  }
  if (has("count")) f.count = static_cast<int>(integer(j.at("count"), "count", 1, 1000));
  if (has("abort_code")) f.abort_code = static_cast<std::uint32_t>(integer(j.at("abort_code"), "abort_code", 1, std::numeric_limits<std::uint32_t>::max()));
  if (f.kind == K::alarm) {
    if (!has("code")) fail(fmt::format("{} is missing: kind \"alarm\" needs an alarm code of the product", field("code")));
    f.alarm = text(j.at("code"), "code");
  }
  if (f.kind == K::collision) {
    if (!has("position")) fail(fmt::format("{} is missing: kind \"collision\" needs the obstacle's position", field("position")));
    f.position = real(j.at("position"), "position");
  }
  if (has("load_scale")) {
    f.load_scale = real(j.at("load_scale"), "load_scale");
    if (!(f.load_scale > 0.0)) fail(fmt::format("{}: {} must be > 0", field("load_scale"), f.load_scale));
  }
  if (has("force")) f.force = real(j.at("force"), "force");
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
  } catch (const json::parse_error& e) {
    fail(fmt::format("not a JSON request: {}", e.what()));
  }
  if (!j.is_object()) fail("a request is a JSON object with an \"op\"");
  if (!j.contains("op") || !j.at("op").is_string()) fail("\"op\" is missing (inject, clear, clear_all, list)");
  const std::string op = j.at("op").get<std::string>();
  const std::set<std::string> allowed = op == "inject" ? std::set<std::string>{"op", "fault"}
                                        : op == "clear" ? std::set<std::string>{"op", "id"}
                                                        : std::set<std::string>{"op"};
  ControlRequest r;
  if (op == "inject") r.op = ControlRequest::Op::inject;
  else if (op == "clear") r.op = ControlRequest::Op::clear;
  else if (op == "clear_all") r.op = ControlRequest::Op::clear_all;
  else if (op == "list") r.op = ControlRequest::Op::list;
  else fail(fmt::format("unknown op \"{}\" (inject, clear, clear_all, list)", op));
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
  json faults = json::array();
  for (const FaultStatus& f : reply.faults) {
    json o{{"id", f.id}, {"kind", f.kind}, {"description", f.description}, {"elapsed_ns", f.elapsed}};
    o["remaining_ns"] = f.remaining < 0 ? json(nullptr) : json(f.remaining);
    faults.push_back(std::move(o));
  }
  j["faults"] = std::move(faults);
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
    for (const json& f : j.value("faults", json::array())) {
      const json& rem = f.at("remaining_ns");
      r.faults.push_back({f.at("id").get<int>(), f.at("kind").get<std::string>(), f.at("description").get<std::string>(),
                          f.at("elapsed_ns").get<Nanos>(), rem.is_null() ? Nanos{-1} : rem.get<Nanos>()});
    }
    return r;
  } catch (const json::exception& e) {
    throw ProtocolError(fmt::format("garbled reply from vdrive: {}", e.what()));
  }
}

}  // namespace vdrive::control
