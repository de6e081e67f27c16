// The JSON API's routes (docs/web.md; assets/openapi.json describes them). Every handler answers
// JSON; a refusal is a 4xx with {"error": "..."} naming what was wrong.
#include <fmt/format.h>
#include <httplib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <variant>

#include "common/time_text.hpp"
#include "ethercat/slave_ref.hpp"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/control/signal_requests.hpp"
#include "vdrive/fault/fault_fields.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/profile/product_profile.hpp"
#include "plant/plant.hpp"
#include "vdrive/web/od_api.hpp"
#include "vdrive/web/web_context.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;

void send(httplib::Response& res, const ApiResult& r) {
  res.status = r.status;
  res.set_content(r.body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

ApiResult loop_busy() { return api_error(503, "the line's event loop did not answer in time; try again"); }

// A request's JSON body, or the 400 that says why it is none.
std::variant<json, ApiResult> body_of(const httplib::Request& req) {
  try {
    return json::parse(req.body);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number too large for a double
    return api_error(400, fmt::format("the body is not JSON: {}", e.what()));
  }
}

// "?since=5&slave=2": a whole number, or the 400 naming the parameter.
std::variant<std::uint64_t, ApiResult> number_param(const httplib::Request& req, const char* name, std::uint64_t otherwise,
                                                    std::uint64_t max = std::numeric_limits<std::uint64_t>::max()) {
  if (!req.has_param(name)) return otherwise;
  const std::string v = req.get_param_value(name);
  std::uint64_t n = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || ec != std::errc{} || end != v.data() + v.size() || n > max)
    return api_error(400, fmt::format("query parameter \"{}\": '{}' is not a whole number{}", name, v,
                                      max != std::numeric_limits<std::uint64_t>::max() ? fmt::format(" from 0 to {}", max) : ""));
  return n;
}

// A slave from the path, by position (from 1) or station address ("0x1002"), as its index; or
// the 404 that says which there are.
std::variant<std::size_t, ApiResult> slave_of(const WebContext& c, const std::string& text) {
  try {
    return ecat::slave_index(ecat::parse_slave_ref(text), c.record.stations());
  } catch (const std::invalid_argument& e) {
    return api_error(404, fmt::format("no slave {}: {}", text, e.what()));
  }
}

// "?slave=2" or "?slave=0x1002" as a position (0: absent, every slave), or the 400 naming it.
std::variant<std::uint64_t, ApiResult> slave_param(const httplib::Request& req, const WebContext& c) {
  if (!req.has_param("slave")) return std::uint64_t{0};
  const std::string v = req.get_param_value("slave");
  if (v == "0") return std::uint64_t{0};
  try {
    return std::uint64_t{ecat::slave_index(ecat::parse_slave_ref(v), c.record.stations()) + 1};
  } catch (const std::invalid_argument& e) {
    return api_error(400, fmt::format("query parameter \"slave\": {}", e.what()));
  }
}

// A request about slave index `i` that a later part of the run serves goes on to that part
// (PartPages), with `rest` after "/api/v1/slaves/POS" and the request's query; true when it did.
bool forwarded(const WebContext& c, std::size_t i, const httplib::Request& req, httplib::Response& res, const std::string& rest) {
  if (c.record.served_here(i) || c.parts == nullptr) return false;
  std::string path = rest;
  if (!req.params.empty()) path.append("?").append(httplib::detail::params_to_query_str(req.params));
  send(res, c.parts->call_for_slave(i, req.method, path, req.body));
  return true;
}

json fault_status_json(const control::FaultStatus& f) {
  return {{"id", f.id}, {"kind", f.kind}, {"description", f.description}, {"elapsed_ns", f.elapsed}, {"remaining_ns", f.remaining}};
}

ApiResult reply_result(const control::ControlReply& r, int ok_status, json body) {
  if (r.ok()) return {ok_status, std::move(body)};
  switch (r.status) {
    case control::ControlReply::Status::bad_request: return api_error(400, r.error);
    case control::ControlReply::Status::denied: return api_error(403, r.error);
    default: return api_error(503, r.error);
  }
}

json signals_json(const control::ControlReply& r) {
  json list = json::array();
  for (const control::SignalStatus& s : r.signals)
    list.push_back({{"name", s.name}, {"point", s.point}, {"type", s.type}, {"value", s.value}});
  return {{"signals", std::move(list)}};
}

void add_line_routes(httplib::Server& s, WebContext& c) {
  s.Get("/api/v1/line", [&c](const httplib::Request&, httplib::Response& res) { send(res, {200, c.record.line(c.clock.now())}); });
  s.Get("/api/v1/samples", [&c](const httplib::Request& req, httplib::Response& res) {
    const auto since = number_param(req, "since", 0);
    const auto slave = slave_param(req, c);
    if (const auto* e = std::get_if<ApiResult>(&since)) return send(res, *e);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    json j = c.record.samples(std::get<std::uint64_t>(since), static_cast<int>(std::get<std::uint64_t>(slave)));
    j["period_ns"] = 20'000'000;
    send(res, {200, std::move(j)});
  });
  const auto events = [&c](const httplib::Request& req, httplib::Response& res, bool csv) {
    const auto since = number_param(req, "since", 0);
    const auto slave = slave_param(req, c);
    if (const auto* e = std::get_if<ApiResult>(&since)) return send(res, *e);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    const std::string kind = req.has_param("kind") ? req.get_param_value("kind") : "";
    const int n = static_cast<int>(std::get<std::uint64_t>(slave));
    if (csv) {
      res.set_header("Content-Disposition", "attachment; filename=\"vdrive-events.csv\"");
      res.set_content(c.record.events_csv(kind, n), "text/csv");
    } else {
      send(res, {200, c.record.events(std::get<std::uint64_t>(since), kind, n)});
    }
  };
  s.Get("/api/v1/events", [events](const httplib::Request& req, httplib::Response& res) { events(req, res, false); });
  s.Get("/api/v1/events.csv", [events](const httplib::Request& req, httplib::Response& res) { events(req, res, true); });
}

// The product's alarm table, for the `code` of an alarm fault and for reading alarm codes.
void add_alarm_routes(httplib::Server& s, WebContext& c) {
  s.Get(R"(/api/v1/slaves/([^/]+)/alarms)", [&c](const httplib::Request& req, httplib::Response& res) {
    const auto slave = slave_of(c, req.matches[1]);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    if (forwarded(c, std::get<std::size_t>(slave), req, res, "/alarms")) return;
    json alarms = json::array();
    const profile::ProductProfile* p = c.record.slave(std::get<std::size_t>(slave)).profile;
    for (const profile::AlarmSpec& a : p->alarms)
      alarms.push_back({{"code", a.code}, {"name", a.name_en.empty() ? a.name : a.name_en}, {"error_code", a.error_code},
                        {"al_status_code", a.al_status_code}, {"warning", a.warning}, {"clearable", a.clearable}});
    send(res, {200, {{"alarms", std::move(alarms)}}});
  });
}

void add_object_routes(httplib::Server& s, WebContext& c) {
  s.Get(R"(/api/v1/slaves/([^/]+)/objects)", [&c](const httplib::Request& req, httplib::Response& res) {
    const auto slave = slave_of(c, req.matches[1]);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    if (forwarded(c, std::get<std::size_t>(slave), req, res, "/objects")) return;
    const std::string q = req.has_param("q") ? req.get_param_value("q") : "";
    send(res, {200, list_entries(*c.dictionaries[std::get<std::size_t>(slave)], q)});
  });
  // Index and subindex of the path, or the 400 naming which is no number.
  const auto address = [](const httplib::Request& req) -> std::variant<std::pair<std::uint16_t, std::uint8_t>, ApiResult> {
    const std::optional<std::uint32_t> index = parse_object_number(req.matches[2], 0xFFFF);
    const std::optional<std::uint32_t> sub = parse_object_number(req.matches[3], 0xFF);
    if (!index) return api_error(400, fmt::format("'{}' is not an object index (0x0000-0xFFFF, e.g. 0x6040)", std::string(req.matches[2])));
    if (!sub) return api_error(400, fmt::format("'{}' is not a subindex (0-255 or 0x00-0xFF)", std::string(req.matches[3])));
    return std::pair{static_cast<std::uint16_t>(*index), static_cast<std::uint8_t>(*sub)};
  };
  const std::string entry = R"(/api/v1/slaves/([^/]+)/objects/([^/]+)/([^/]+))";
  s.Get(entry, [&c, address](const httplib::Request& req, httplib::Response& res) {
    const auto slave = slave_of(c, req.matches[1]);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    const auto at = address(req);
    if (const auto* e = std::get_if<ApiResult>(&at)) return send(res, *e);
    if (forwarded(c, std::get<std::size_t>(slave), req, res, fmt::format("/objects/{}/{}", std::string(req.matches[2]), std::string(req.matches[3])))) return;
    // Plain copies: a lambda may not capture structured bindings before C++20 compilers caught up
    // (clang 14, the fuzz build's).
    const std::uint16_t index = std::get<0>(at).first;
    const std::uint8_t sub = std::get<0>(at).second;
    ApiResult result = loop_busy();
    c.calls.run([&](Nanos) { result = read_entry(c.network, std::get<std::size_t>(slave), index, sub); }, kLoopTimeout);
    send(res, result);
  });
  s.Put(entry, [&c, address](const httplib::Request& req, httplib::Response& res) {
    const auto slave = slave_of(c, req.matches[1]);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    const auto at = address(req);
    if (const auto* e = std::get_if<ApiResult>(&at)) return send(res, *e);
    if (forwarded(c, std::get<std::size_t>(slave), req, res, fmt::format("/objects/{}/{}", std::string(req.matches[2]), std::string(req.matches[3])))) return;
    const std::uint16_t index = std::get<0>(at).first;  // plain copies, as above
    const std::uint8_t sub = std::get<0>(at).second;
    const std::size_t i = std::get<std::size_t>(slave);
    const od::EntryDesc* desc = c.dictionaries[i]->find(index, sub);
    if (desc == nullptr) {  // as the slave answers a master: the store says which is missing
      ApiResult result = loop_busy();
      c.calls.run([&](Nanos) { result = read_entry(c.network, i, index, sub); }, kLoopTimeout);
      return send(res, result);
    }
    const auto body = body_of(req);
    if (const auto* e = std::get_if<ApiResult>(&body)) return send(res, *e);
    const auto data = encode_value(*desc, std::get<json>(body));
    if (const auto* e = std::get_if<ApiResult>(&data)) return send(res, *e);
    ApiResult result = loop_busy();
    c.calls.run([&](Nanos) { result = write_entry(c.network, i, index, sub, std::get<std::vector<std::uint8_t>>(data)); }, kLoopTimeout);
    const std::string what = fmt::format("{:04X}h:{:02X} {}", index, sub, desc->name);
    if (result.status == 200)
      c.record.note(static_cast<int>(i + 1), "od_write", 0, 0, fmt::format("{} := {}", what, result.body.at("value").dump()), c.clock.now());
    else if (result.body.contains("abort_code"))
      c.record.note(static_cast<int>(i + 1), "od_abort", 0, 0,
                    fmt::format("{} refused: {} {}", what, result.body.at("abort_code").get<std::string>(),
                                result.body.at("abort_text").get<std::string>()), c.clock.now());
    send(res, result);
  });
}

void add_fault_routes(httplib::Server& s, WebContext& c) {
  s.Get("/api/v1/fault-kinds", [](const httplib::Request&, httplib::Response& res) {
    json kinds = json::array();
    for (const fault::FaultKindInfo& k : fault::fault_catalogue()) {
      json fields = json::array();
      for (const fault::FaultFieldInfo& f : fault::fault_fields(k.kind)) {
        json field = {{"name", f.name}, {"type", f.type}, {"required", f.required}, {"help", f.help}};
        field["default"] = f.required ? json(nullptr) : json(std::string(f.default_value));
        json choices = json::array();
        for (std::string_view rest = f.choices; !rest.empty();) {
          const std::size_t comma = rest.find(',');
          choices.push_back(std::string(rest.substr(0, comma)));
          rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
        }
        field["choices"] = std::move(choices);
        fields.push_back(std::move(field));
      }
      kinds.push_back({{"kind", k.name}, {"layer", std::string(fault::name(k.layer))}, {"one_shot", k.one_shot},
                       {"summary", k.summary}, {"fields", std::move(fields)}});
    }
    send(res, {200, {{"kinds", std::move(kinds)}}});
  });
  s.Get("/api/v1/faults", [&c](const httplib::Request&, httplib::Response& res) {
    control::ControlRequest r;
    r.op = control::ControlRequest::Op::list;
    const control::ControlReply reply = c.fault_call(r, R"({"op":"list"})");
    json faults = json::array();
    for (const control::FaultStatus& f : reply.faults) faults.push_back(fault_status_json(f));
    json scheduled = json::array();
    {
      const std::lock_guard<std::mutex> lock(c.scheduled_mutex);
      for (const ScheduledFault& f : c.scheduled) scheduled.push_back({{"ticket", f.ticket}, {"at_ns", f.at}, {"fault", f.fault}});
    }
    send(res, reply_result(reply, 200, {{"faults", std::move(faults)}, {"scheduled", std::move(scheduled)}}));
  });
  s.Post("/api/v1/faults", [&c](const httplib::Request& req, httplib::Response& res) {
    const auto body = body_of(req);
    if (const auto* e = std::get_if<ApiResult>(&body)) return send(res, *e);
    json fault = std::get<json>(body);
    if (!fault.is_object()) return send(res, api_error(400, "the body must be a fault object, e.g. {\"kind\":\"jam\",\"slave\":1}"));
    std::optional<Nanos> after;
    if (fault.contains("after")) {
      const json a = fault.at("after");
      fault.erase("after");
      if (!a.is_string() || !parse_time(a.get<std::string>()))
        return send(res, api_error(400, fmt::format("\"after\": {} is not a time with a unit (e.g. \"2s\", \"250ms\")", a.dump())));
      after = parse_time(a.get<std::string>());
    }
    control::ControlRequest r;
    const std::string line = json{{"op", "inject"}, {"fault", fault}}.dump();
    try {
      r = control::parse_request(line);
    } catch (const control::ProtocolError& e) {
      return send(res, api_error(400, e.what()));
    }
    if (r.fault.slave > static_cast<int>(c.record.size()))
      return send(res, api_error(400, fmt::format("fault field \"slave\": no slave {} (the line has slaves 1 to {})", r.fault.slave, c.record.size())));
    if (after && *after > 0) {
      if (c.faults == nullptr && !c.route) return send(res, api_error(503, "this vdrive takes no fault requests"));
      const std::lock_guard<std::mutex> lock(c.scheduled_mutex);
      if (c.scheduled.size() >= 64) return send(res, api_error(429, "64 faults are already scheduled; wait or clear them"));
      const int ticket = c.next_ticket++;
      c.scheduled.push_back({ticket, c.clock.now() + *after, r, line, fault});
      return send(res, {202, {{"scheduled", ticket}}});
    }
    const control::ControlReply reply = c.fault_call(r, line);
    send(res, reply_result(reply, 201, {{"id", reply.id}}));
  });
  s.Delete(R"(/api/v1/faults/([^/]+))", [&c](const httplib::Request& req, httplib::Response& res) {
    const std::optional<std::uint32_t> id = parse_object_number(req.matches[1], std::numeric_limits<int>::max());
    if (!id || *id < 1) return send(res, api_error(400, fmt::format("'{}' is not a fault id (a whole number from 1)", std::string(req.matches[1]))));
    control::ControlRequest r;
    r.op = control::ControlRequest::Op::clear;
    r.id = static_cast<int>(*id);
    const control::ControlReply reply = c.fault_call(r, json{{"op", "clear"}, {"id", r.id}}.dump());
    if (reply.status == control::ControlReply::Status::bad_request) return send(res, api_error(404, reply.error));
    send(res, reply_result(reply, 200, {{"cleared", 1}}));
  });
  s.Delete("/api/v1/faults", [&c](const httplib::Request&, httplib::Response& res) {
    std::size_t dropped = 0;
    {
      const std::lock_guard<std::mutex> lock(c.scheduled_mutex);
      dropped = c.scheduled.size();
      c.scheduled.clear();
    }
    control::ControlRequest r;
    r.op = control::ControlRequest::Op::clear_all;
    const control::ControlReply reply = c.fault_call(r, R"({"op":"clear_all"})");
    send(res, reply_result(reply, 200, {{"cleared", reply.cleared}, {"unscheduled", dropped}}));
  });
}

void add_plant_and_signal_routes(httplib::Server& s, WebContext& c) {
  s.Post(R"(/api/v1/slaves/([^/]+)/plant)", [&c](const httplib::Request& req, httplib::Response& res) {
    const auto slave = slave_of(c, req.matches[1]);
    if (const auto* e = std::get_if<ApiResult>(&slave)) return send(res, *e);
    if (forwarded(c, std::get<std::size_t>(slave), req, res, "/plant")) return;
    const auto body = body_of(req);
    if (const auto* e = std::get_if<ApiResult>(&body)) return send(res, *e);
    const json& j = std::get<json>(body);
    if (!j.is_object() || j.empty()) return send(res, api_error(400, "the body must be an object with \"external_load\" and/or \"brake\""));
    std::optional<double> load;
    std::optional<std::optional<bool>> brake;
    for (const auto& [key, v] : j.items()) {
      if (key == "external_load") {
        if (!v.is_number() || !std::isfinite(v.get<double>()))
          return send(res, api_error(400, fmt::format("\"external_load\": expected a number (N or N m), got {}", v.dump())));
        load = v.get<double>();
      } else if (key == "brake") {
        const std::string b = v.is_string() ? v.get<std::string>() : "";
        if (b == "released") brake = std::optional<bool>(true);
        else if (b == "engaged") brake = std::optional<bool>(false);
        else if (b == "drive") brake = std::optional<bool>();
        else return send(res, api_error(400, fmt::format("\"brake\": {} is not released, engaged or drive", v.dump())));
      } else {
        return send(res, api_error(400, fmt::format("\"{}\" is not a plant change (external_load, brake); jam, collision, "
                                                    "load_change and brake_failure are faults (POST /api/v1/faults)", key)));
      }
    }
    const std::size_t i = std::get<std::size_t>(slave);
    ApiResult result = loop_busy();
    c.calls.run([&](Nanos) {
      plant::Plant* p = c.network.firmware(i).plant();
      if (p == nullptr || p->axis_count() == 0) {
        result = api_error(409, fmt::format("slave {} has no plant", i + 1));
        return;
      }
      if (load) p->set_external_load(0, *load);
      if (brake) p->set_brake_control(0, *brake);
      result = {200, {{"ok", true}}};
    }, kLoopTimeout);
    if (result.status == 200) {
      std::string text;
      if (load) text = fmt::format("external load {:g}", *load);
      if (brake) text += fmt::format("{}brake {}", text.empty() ? "" : ", ", !*brake ? "driven by the drive" : **brake ? "released" : "engaged");
      c.record.note(static_cast<int>(i + 1), "plant_set", 0, 0, text, c.clock.now());
    }
    send(res, result);
  });
  // Every part's signals through the run's router; else this process's, on the loop thread.
  const auto signal_call = [&c](const control::ControlRequest& r, std::string_view line) {
    if (c.route) return c.route(r, line);
    control::ControlReply reply = control::error_reply(control::ControlReply::Status::failed, "the line's event loop did not answer in time");
    c.calls.run([&](Nanos) { reply = control::handle_signal_request(c.network, r); }, kLoopTimeout);
    return reply;
  };
  s.Get("/api/v1/signals", [signal_call](const httplib::Request&, httplib::Response& res) {
    control::ControlRequest r;
    r.op = control::ControlRequest::Op::signals;
    const control::ControlReply reply = signal_call(r, R"({"op":"signals"})");
    send(res, reply_result(reply, 200, signals_json(reply)));
  });
  s.Put(R"(/api/v1/signals/(.+))", [signal_call](const httplib::Request& req, httplib::Response& res) {
    const auto body = body_of(req);
    if (const auto* e = std::get_if<ApiResult>(&body)) return send(res, *e);
    const json& j = std::get<json>(body);
    if (!j.is_object() || !j.contains("value") || j.size() != 1) return send(res, api_error(400, "the body must be {\"value\": N}"));
    control::ControlRequest r;
    const std::string line = json{{"op", "signal_set"}, {"signal", std::string(req.matches[1])}, {"value", j.at("value")}}.dump();
    try {
      r = control::parse_request(line);
    } catch (const control::ProtocolError& e) {
      return send(res, api_error(400, e.what()));
    }
    const control::ControlReply reply = signal_call(r, line);
    send(res, reply_result(reply, 200, signals_json(reply)));
  });
}

}  // namespace

control::ControlReply WebContext::fault_call(const control::ControlRequest& request, std::string_view line) {
  if (route) return route(request, line);
  if (faults == nullptr) return control::error_reply(control::ControlReply::Status::failed, "this vdrive takes no fault requests");
  control::ControlReply reply = control::error_reply(control::ControlReply::Status::failed, "the line's event loop did not answer in time");
  calls.run([&](Nanos now) { reply = faults->handle(request, now); }, kLoopTimeout);
  return reply;
}

void add_api_routes(httplib::Server& server, WebContext& context) {
  add_line_routes(server, context);
  add_object_routes(server, context);
  add_alarm_routes(server, context);
  add_fault_routes(server, context);
  add_plant_and_signal_routes(server, context);
}

}  // namespace vdrive::web
