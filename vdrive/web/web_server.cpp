#include "vdrive/web/web_server.hpp"

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>

#include "vdrive/control/fault_service.hpp"
#include "vdrive/control/request_rate.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/telemetry/loop_services.hpp"
#include "vdrive/telemetry/sampler.hpp"
#include "vdrive/web/web_assets.hpp"
#include "vdrive/web/web_context.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;
using namespace std::chrono_literals;

constexpr std::size_t kMaxBody = 64 * 1024;
constexpr int kMaxStreams = 6;
// Each live stream holds a thread for as long as it is open, and a browser keeps a few more
// connections alive: enough threads that the API is still answered with every stream open.
constexpr std::size_t kServerThreads = 16;
constexpr auto kStreamPeriod = 40ms;  // 25 updates a second, paced by deadline
constexpr auto kPartsPeriod = 100ms;  // the later parts' pages read 10 times a second

// Equal in time independent of where they differ.
bool same(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d |= static_cast<unsigned char>(a[i] ^ b[i]);
  return d == 0;
}

bool changes_something(const httplib::Request& req) { return req.method != "GET" && req.method != "HEAD" && req.method != "OPTIONS"; }

void refuse(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(json{{"error", message}}.dump(), "application/json");
}

}  // namespace

std::string new_token() {
  std::random_device random;
  std::string t;
  for (int i = 0; i < 4; ++i) t += fmt::format("{:08x}", random());
  return t;
}

struct WebServer::Impl {
  network::Network& network;
  const Clock& clock;
  WebServerOptions options;
  std::string token;
  control::RequestRate change_rate;  // requests that change the line (the others only read)
  telemetry::Sampler sampler;
  LoopCalls calls;
  telemetry::LoopServices services;
  PartPages parts;
  LineRecord record;
  WebContext context;
  httplib::Server server;
  int port = 0;
  std::atomic<bool> stopping{false};
  std::atomic<int> streams{0};
  std::thread pump_thread, server_thread, parts_thread;

  Impl(network::Network& n, const Clock& c, const runtime::LoopCounters& counters, control::FaultService* faults,
       WebServerOptions o, std::function<void()> wake)
      : network(n), clock(c), options(std::move(o)),
        token(!options.token.empty() ? options.token : options.address.loopback() ? "" : new_token()),
        sampler(n, options.sample_rate_hz, telemetry::SamplerSources{&counters, nullptr, faults != nullptr ? &faults->injector() : nullptr}),
        calls(std::move(wake)), services(&sampler, &calls),
        parts(options.parts, options.parts_token),
        record(slave_infos(n), LineIdentity{options.source, options.interface, options.version, !token.empty()},
               options.origin.value_or(c.now()), parts.slaves()),
        context{n, c, faults, record, calls, {}, {}, {}, 1, nullptr, {}} {
    for (std::size_t i = 0; i < n.size(); ++i) context.dictionaries.push_back(&n.firmware(i).objects().dictionary());
    if (options.run_parts > 1) sampler.set_place({0, options.run_part, options.run_parts, 0});
    if (!parts.empty()) context.parts = &parts;
    context.route = options.route;
  }

  bool host_allowed(const httplib::Request& req) const {
    if (!options.address.loopback()) return true;  // the token guards changes
    const std::string host = req.get_header_value("Host");
    const std::string name = host.substr(0, host.rfind(':') == std::string::npos || host.back() == ']' ? host.size() : host.rfind(':'));
    return name.empty() || name == "localhost" || name == "[::1]" || name.rfind("127.", 0) == 0;
  }

  httplib::Server::HandlerResponse guard(const httplib::Request& req, httplib::Response& res) {
    if (!host_allowed(req)) {
      refuse(res, 403, fmt::format("Host '{}' is not this machine: a loopback server answers only localhost and 127.x names",
                                   req.get_header_value("Host")));
      return httplib::Server::HandlerResponse::Handled;
    }
    if (!changes_something(req)) return httplib::Server::HandlerResponse::Unhandled;
    if (!token.empty()) {
      const std::string auth = req.get_header_value("Authorization");
      if (auth.rfind("Bearer ", 0) != 0 || !same(auth.substr(7), token)) {
        refuse(res, 401, "this request changes the line: send the token vdrive printed at start (Authorization: Bearer TOKEN)");
        return httplib::Server::HandlerResponse::Handled;
      }
    }
    if ((req.method == "POST" || req.method == "PUT") && req.get_header_value("Content-Type").rfind("application/json", 0) != 0) {
      refuse(res, 415, "send the body as JSON (Content-Type: application/json)");
      return httplib::Server::HandlerResponse::Handled;
    }
    Nanos wait = 0;
    if (!change_rate.take(&wait)) {
      res.set_header("Retry-After", std::to_string(std::max<Nanos>(1, (wait + 999'999'999) / 1'000'000'000)));
      refuse(res, 429, change_rate.refusal(wait));
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  }

  // One live update: the line, the plot points and events since the client's last update.
  std::string update(std::uint64_t& samples_seen, std::uint64_t& events_seen) {
    json j;
    j["line"] = record.line(clock.now());
    j["samples"] = record.samples(samples_seen, 0);
    j["events"] = record.events(events_seen, "", 0).at("events");
    samples_seen = j["samples"]["seq"].get<std::uint64_t>();
    events_seen = std::max<std::uint64_t>(events_seen, record.event_seq());
    return "event: update\ndata: " + j.dump(-1, ' ', false, json::error_handler_t::replace) + "\n\n";
  }

  void add_page_routes() {
    server.Get("/api/v1/stream", [this](const httplib::Request&, httplib::Response& res) {
      if (streams.fetch_add(1) >= kMaxStreams) {
        streams.fetch_sub(1);
        return refuse(res, 503, fmt::format("{} live streams are open already; close a page or poll /api/v1/line", kMaxStreams));
      }
      auto seen = std::make_shared<std::pair<std::uint64_t, std::uint64_t>>(0, 0);
      res.set_header("Cache-Control", "no-store");
      res.set_chunked_content_provider(
          "text/event-stream",
          [this, seen, next = std::make_shared<std::chrono::steady_clock::time_point>()](std::size_t, httplib::DataSink& sink) {
            // By deadline, so building a large update does not slow the rate.
            const auto now = std::chrono::steady_clock::now();
            if (*next > now) std::this_thread::sleep_until(*next);
            *next = std::max(*next + kStreamPeriod, now);
            if (stopping.load()) return false;
            const std::string chunk = update(seen->first, seen->second);
            return sink.write(chunk.data(), chunk.size());
          },
          [this](bool) { streams.fetch_sub(1); });
    });
    server.Get(R"(/(.*))", [](const httplib::Request& req, httplib::Response& res) {
      const std::string path = req.path == "/api/v1/openapi.json" ? "/openapi.json" : req.path;
      if (req.path.rfind("/api/", 0) == 0 && path == req.path) return refuse(res, 404, fmt::format("no API endpoint GET {}", req.path));
      if (std::optional<Asset> a = find_asset(path)) {
        res.set_content(std::move(a->body), a->content_type);
        return;
      }
      refuse(res, 404, fmt::format("no page {}", req.path));
    });
  }

  // Moves samples into the record; asks the loop for registers and faults; injects scheduled faults.
  void pump() {
    std::vector<SlaveRegisters> registers(network.size());
    auto next_registers = std::chrono::steady_clock::now();
    auto next_faults = next_registers;
    while (!stopping.load()) {
      while (std::optional<telemetry::Sample> s = sampler.pop()) record.add(*s);
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_registers) {
        Nanos copied = 0;
        if (calls.run([&](Nanos now) { read_registers(network, registers); copied = now; }, kLoopTimeout))
          record.set_registers(registers, copied);
        next_registers = now + 100ms;
      }
      // Through the run's router the list waits for every part: the parts' pump takes it then.
      if (now >= next_faults && context.faults != nullptr && !context.route) {
        list_faults();
        next_faults = now + 250ms;
      }
      inject_due();
      std::this_thread::sleep_for(20ms);
    }
  }

  void list_faults() {
    control::ControlRequest r;
    r.op = control::ControlRequest::Op::list;
    const control::ControlReply reply = context.fault_call(r, R"({"op":"list"})");
    if (reply.ok()) record.set_faults(reply.faults);
  }

  // The later parts' pages, and the run's faults through its router, into the record, on a
  // thread of its own: a part that does not answer holds up only this, never the samples' pump.
  void pump_parts() {
    auto next = std::chrono::steady_clock::now();
    while (!stopping.load()) {
      if (!parts.empty()) parts.poll(record, clock.now());
      if (context.route) list_faults();
      next = std::max(next + kPartsPeriod, std::chrono::steady_clock::now());
      while (!stopping.load() && std::chrono::steady_clock::now() < next) std::this_thread::sleep_for(10ms);
    }
  }

  void inject_due() {
    std::vector<ScheduledFault> due;
    {
      const std::lock_guard<std::mutex> lock(context.scheduled_mutex);
      const Nanos now = clock.now();
      for (auto it = context.scheduled.begin(); it != context.scheduled.end();) {
        if (it->at <= now) {
          due.push_back(std::move(*it));
          it = context.scheduled.erase(it);
        } else {
          ++it;
        }
      }
    }
    for (const ScheduledFault& f : due) {
      const control::ControlReply reply = context.fault_call(f.request, f.line);
      if (!reply.ok()) record.note(f.request.fault.slave, "fault_refused", f.ticket, 0, reply.error, clock.now());
    }
  }

  void start() {
    server.set_payload_max_length(kMaxBody);
    server.new_task_queue = [] { return new httplib::ThreadPool(kServerThreads); };
    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) { return guard(req, res); });
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr e) {
      std::string what = "unknown error";
      try {
        std::rethrow_exception(e);
      } catch (const std::exception& x) {
        what = x.what();
      } catch (...) {
      }
      refuse(res, 500, "the server failed: " + what);
    });
    server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;
      if (res.status == 413) return refuse(res, 413, fmt::format("the body is larger than {} bytes", kMaxBody));
      if (res.status == 404) return refuse(res, 404, fmt::format("no endpoint {} {}", req.method, req.path));
      refuse(res, res.status, fmt::format("HTTP {}", res.status));
    });
    add_api_routes(server, context);
    add_page_routes();
    const std::string& host = options.address.host;
    port = options.address.port == 0 ? server.bind_to_any_port(host) : (server.bind_to_port(host, options.address.port) ? options.address.port : -1);
    if (port <= 0)
      throw WebError(fmt::format("--web {}:{}: cannot listen there ({}; another program may use the port)", host, options.address.port,
                                 std::strerror(errno != 0 ? errno : EADDRINUSE)));
    server_thread = std::thread([this] { server.listen_after_bind(); });
    pump_thread = std::thread([this] { pump(); });
    if (!parts.empty() || context.route) parts_thread = std::thread([this] { pump_parts(); });
  }

  void stop() {
    stopping.store(true);
    calls.close();  // the loop may have stopped already: nobody would answer
    server.stop();
    if (server_thread.joinable()) server_thread.join();
    if (pump_thread.joinable()) pump_thread.join();
    if (parts_thread.joinable()) parts_thread.join();
  }
};

WebServer::WebServer(network::Network& network, const Clock& clock, const runtime::LoopCounters& counters,
                     control::FaultService* faults, WebServerOptions options, std::function<void()> wake)
    : impl_(std::make_unique<Impl>(network, clock, counters, faults, std::move(options), std::move(wake))) {
  impl_->start();
}

WebServer::~WebServer() { impl_->stop(); }

runtime::LoopService& WebServer::service() { return impl_->services; }

std::string WebServer::url() const {
  WebAddress shown = impl_->options.address;
  shown.port = impl_->port;
  return impl_->token.empty() ? shown.url() : shown.url() + "#token=" + impl_->token;
}

const std::string& WebServer::token() const { return impl_->token; }

int WebServer::port() const { return impl_->port; }

LineRecord& WebServer::record() { return impl_->record; }

void WebServer::note(int slave, const std::string& kind, const std::string& text) {
  impl_->record.note(slave, kind, 0, 0, text, impl_->clock.now());
}

}  // namespace vdrive::web
