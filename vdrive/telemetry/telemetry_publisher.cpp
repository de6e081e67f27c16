// The telemetry thread: samples to DDS, control requests to the loop. See telemetry_publisher.hpp.
#include "vdrive/telemetry/telemetry_publisher.hpp"

#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <string>
#include <utility>

#include "TelemetryPubSubTypes.h"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/control/request_rate.hpp"
#include "vdrive/telemetry/dds_node.hpp"

namespace vdrive::telemetry {
namespace dds = eprosima::fastdds::dds;
namespace msg = vdrive::msg::dds_;
using eprosima::fastrtps::types::ReturnCode_t;

struct TelemetryPublisher::Impl {
  Impl(Sampler& s, int domain, std::function<void()> w, PublisherOptions o)
      : sampler(s), node(domain), axis(node.writer(Topic::axis_state)), bus(node.writer(Topic::bus_state)),
        events(node.writer(Topic::events)), replies(node.writer(Topic::control_reply)),
        requests(o.take_requests ? node.reader(Topic::control_request) : nullptr), wake(std::move(w)), route(std::move(o.route)) {}

  // Publishes everything queued; returns how many.
  std::uint64_t drain() {
    std::uint64_t n = 0;
    while (std::optional<Sample> s = sampler.pop()) {
      std::visit([this](const auto& v) { write(v); }, *s);
      ++n;
    }
    return n;
  }

  void write(const AxisSample& a) {
    msg::AxisState_ m;
    m.time_ns(a.time);
    m.slave(a.slave);
    m.station(a.station);
    m.al_state(a.al_state);
    m.al_status_code(a.al_status_code);
    m.statusword(a.statusword);
    m.controlword(a.controlword);
    m.mode(a.mode);
    m.position(a.position);
    m.velocity(a.velocity);
    m.torque(a.torque);
    m.following_error(a.following_error);
    m.error_code(a.error_code);
    m.winding_temperature_c(a.winding_c);
    m.housing_temperature_c(a.housing_c);
    axis->write(&m);
  }

  void write(const BusSample& b) {
    msg::BusState_ m;
    m.time_ns(b.time);
    m.slave(b.slave);
    m.station(b.station);
    m.al_state(b.al_state);
    m.al_status_code(b.al_status_code);
    m.frames_in(b.frames_in);
    m.frames_out(b.frames_out);
    m.frames_dropped(b.frames_dropped);
    m.send_failed(b.send_failed);
    m.rx_errors(b.rx_errors);
    m.lost_links(b.lost_links);
    m.samples_dropped(b.samples_dropped);
    m.turnaround_last_ns(b.turnaround_last);
    m.turnaround_min_ns(b.turnaround_min);
    m.turnaround_mean_ns(b.turnaround_mean);
    m.turnaround_max_ns(b.turnaround_max);
    m.host_stalls(b.host_stalls);
    m.longest_host_stall_ns(b.longest_host_stall);
    bus->write(&m);
  }

  void write(const EventSample& e) {
    msg::Event_ m;
    m.time_ns(e.time);
    m.slave(e.slave);
    m.kind(event_kind_name(e.kind));
    m.value(e.value);
    m.previous(e.previous);
    m.text(e.text.data());
    events->write(&m);
  }

  void reply(const std::string& client, std::uint32_t id, const control::ControlReply& r) {
    msg::ControlReply_ m;
    m.client(client);
    m.request_id(id);
    m.reply(control::format_reply(r));
    replies->write(&m);
  }

  // Control requests in: parsed here, carried out on the loop thread.
  void take_requests() {
    if (requests == nullptr) return;
    msg::ControlRequest_ m;
    dds::SampleInfo info;
    while (requests->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      Nanos wait = 0;
      if (!rate.take(&wait)) {
        reply(m.client(), m.request_id(), control::error_reply(control::ControlReply::Status::failed, rate.refusal(wait)));
        continue;
      }
      try {
        TelemetryRequest r = parse_telemetry_request(m.request());
        if (r.kind == TelemetryRequest::Kind::fault && route) {
          const control::ControlReply answer = route(r.fault, m.request());
          if (!answer.ok()) spdlog::warn("telemetry control request from {} refused: {}", m.client(), answer.error);
          reply(m.client(), m.request_id(), answer);
          continue;
        }
        r.ticket = next_ticket++;
        const std::uint64_t ticket = r.ticket;
        if (!sampler.request(std::move(r))) {
          reply(m.client(), m.request_id(), control::error_reply(control::ControlReply::Status::failed, "the event loop has too many requests pending"));
          continue;
        }
        pending.emplace(ticket, std::make_pair(m.client(), m.request_id()));
        if (wake) wake();
      } catch (const control::ProtocolError& e) {
        spdlog::warn("telemetry control request from {} refused: {}", m.client(), e.what());
        reply(m.client(), m.request_id(), control::error_reply(control::ControlReply::Status::bad_request, e.what()));
      }
    }
  }

  void send_replies() {
    while (std::optional<TelemetryReply> r = sampler.reply()) {
      const auto it = pending.find(r->ticket);
      if (it == pending.end()) continue;
      if (!r->reply.ok()) spdlog::warn("telemetry control request from {} refused: {}", it->second.first, r->reply.error);
      reply(it->second.first, it->second.second, r->reply);
      pending.erase(it);
    }
  }

  Sampler& sampler;
  DdsNode node;
  dds::DataWriter* axis;
  dds::DataWriter* bus;
  dds::DataWriter* events;
  dds::DataWriter* replies;
  dds::DataReader* requests;  // null: this process takes no requests
  std::function<void()> wake;
  FaultRoute route;
  std::map<std::uint64_t, std::pair<std::string, std::uint32_t>> pending;  // ticket -> requester
  std::uint64_t next_ticket = 1;
  control::RequestRate rate;  // over the bound: answered here, never queued for the loop
};

TelemetryPublisher::TelemetryPublisher(Sampler& sampler, int domain, std::function<void()> wake, PublisherOptions options)
    : impl_(std::make_unique<Impl>(sampler, domain, std::move(wake), std::move(options))) {
  // Half a sample period between rounds (1..10 ms): the queue holds kQueueSize samples, far more
  // than arrive in that time, and control requests wait at most that long.
  const auto pause = std::chrono::nanoseconds(std::clamp<Nanos>(sampler.period() / 2, 1'000'000, 10'000'000));
  thread_ = std::thread([this, pause] {
    while (!stop_.load(std::memory_order_relaxed)) {
      const std::uint64_t n = impl_->drain();
      published_.store(published_.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
      impl_->take_requests();
      impl_->send_replies();
      if (n == 0) std::this_thread::sleep_for(pause);
    }
    impl_->drain();
  });
}

TelemetryPublisher::~TelemetryPublisher() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

}  // namespace vdrive::telemetry
