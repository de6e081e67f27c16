#pragma once
// A served line for the web tests: three drives (no master, so they stay in Init), their fault
// control and a WebServer on an ephemeral loopback port, with a thread standing in for the event
// loop (timers, the fault service and the page's service), and an HTTP client on it.
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/station_addresses.hpp"
#include "vdrive/control/fault_service.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/runtime/event_loop.hpp"
#include "vdrive/web/web_server.hpp"

namespace vdrive::web::test {

class WebLine {
public:
  // `base` (optional): the server's other options (a part of a line over processes).
  explicit WebLine(std::string host = "127.0.0.1", std::vector<std::string> drives = {"a6b", "ds5c1", "ds1000a"},
                   const WebServerOptions* base = nullptr)
      : network_(drives, clock_), faults_(network_, nullptr, nullptr) {
    WebServerOptions o;
    if (base != nullptr) o = *base;
    o.address.host = std::move(host);
    o.address.port = 0;
    o.source = "test";
    o.version = "test";
    server_ = std::make_unique<WebServer>(network_, clock_, counters_, &faults_, o);
    loop_ = std::thread([this] {
      while (!stop_.load()) {
        const Nanos now = clock_.now();
        if (const std::uint16_t first = assign_first_.load(); first != 0) {
          assigned_.store(vdrive::test::assign_station_addresses(network_, now, first) ? 1 : 2);
          assign_first_.store(0);
        }
        network_.tick(now);
        faults_.poll(now);
        server_->service().poll(now);
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    });
  }
  ~WebLine() {
    stop_.store(true);
    loop_.join();
    server_.reset();
  }

  WebServer& server() { return *server_; }
  // As a master does at scan, on the loop's thread: station addresses first, first + 1, ...
  bool assign_station_addresses(std::uint16_t first) {
    assigned_.store(0);
    assign_first_.store(first);
    for (int i = 0; i < 1000 && assigned_.load() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return assigned_.load() == 1;
  }
  // This loop never records a stall (it is not serve_once), so a test may: the one writer.
  runtime::HostStalls& stalls() { return counters_.stalls; }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", server_->port());
    c.set_read_timeout(5, 0);
    return c;
  }
  // The JSON of a GET; {} when the request failed.
  nlohmann::json get(const std::string& path) const {
    auto r = client().Get(path.c_str());
    return r ? nlohmann::json::parse(r->body) : nlohmann::json{};
  }

private:
  MonotonicClock clock_;
  network::Network network_;
  runtime::LoopCounters counters_;
  control::FaultService faults_;
  std::unique_ptr<WebServer> server_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint16_t> assign_first_{0};
  std::atomic<int> assigned_{0};  // 0: pending, 1: done, 2: a slave did not take its address
  std::thread loop_;
};

// Waits up to 10 s for `done`.
template <typename F>
bool eventually(F done) {
  for (int i = 0; i < 1000; ++i) {  // up to 10 s: a loaded CI host
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

}  // namespace vdrive::web::test
