// The subscribing and requesting side of the telemetry. See telemetry_client.hpp.
#include "vdrive/telemetry/telemetry_client.hpp"

#include <fastdds/dds/core/condition/WaitSet.hpp>
#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fmt/core.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "TelemetryPubSubTypes.h"
#include "vdrive/control/control_protocol.hpp"
#include "vdrive/telemetry/dds_node.hpp"

namespace vdrive::telemetry {
namespace dds = eprosima::fastdds::dds;
namespace msg = vdrive::msg::dds_;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

AxisSample to_sample(const msg::AxisState_& m) {
  AxisSample a;
  a.time = m.time_ns();
  a.slave = m.slave();
  a.station = m.station();
  a.al_state = m.al_state();
  a.al_status_code = m.al_status_code();
  a.statusword = m.statusword();
  a.controlword = m.controlword();
  a.mode = m.mode();
  a.position = m.position();
  a.velocity = m.velocity();
  a.torque = m.torque();
  a.following_error = m.following_error();
  a.error_code = m.error_code();
  a.winding_c = m.winding_temperature_c();
  a.housing_c = m.housing_temperature_c();
  return a;
}

BusSample to_sample(const msg::BusState_& m) {
  BusSample b;
  b.time = m.time_ns();
  b.slave = m.slave();
  b.station = m.station();
  b.al_state = m.al_state();
  b.al_status_code = m.al_status_code();
  b.frames_in = m.frames_in();
  b.frames_out = m.frames_out();
  b.frames_dropped = m.frames_dropped();
  b.send_failed = m.send_failed();
  b.rx_errors = m.rx_errors();
  b.lost_links = m.lost_links();
  b.samples_dropped = m.samples_dropped();
  b.turnaround_last = m.turnaround_last_ns();
  b.turnaround_min = m.turnaround_min_ns();
  b.turnaround_mean = m.turnaround_mean_ns();
  b.turnaround_max = m.turnaround_max_ns();
  b.host_stalls = m.host_stalls();
  b.longest_host_stall = m.longest_host_stall_ns();
  return b;
}

Event to_event(const msg::Event_& m) {
  return Event{m.time_ns(), m.slave(), m.kind(), m.text(), m.value(), m.previous()};
}

template <typename Message, typename Fn>
std::size_t take_all(dds::DataReader* reader, Fn&& fn) {
  std::size_t n = 0;
  Message m;
  dds::SampleInfo info;
  while (reader->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) continue;
    fn(m);
    ++n;
  }
  return n;
}

}  // namespace

struct TelemetryClient::Impl {
  explicit Impl(int domain) : node(domain) {}
  DdsNode node;
  dds::DataReader* axis = nullptr;
  dds::DataReader* bus = nullptr;
  dds::DataReader* events = nullptr;
  dds::DataWriter* requests = nullptr;
  dds::DataReader* replies = nullptr;
  std::string client = fmt::format("{}:{}", [] {
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    return std::string(host);
  }(), ::getpid());
  std::uint32_t next_id = 1;
};

TelemetryClient::TelemetryClient(int domain) : impl_(std::make_unique<Impl>(domain)) {}
TelemetryClient::~TelemetryClient() = default;

std::size_t TelemetryClient::poll(Nanos wait, const TelemetryHandlers& h) {
  // Readers are created on first use, so a client that only sends requests subscribes to nothing.
  if (h.axis && impl_->axis == nullptr) impl_->axis = impl_->node.reader(Topic::axis_state);
  if (h.bus && impl_->bus == nullptr) impl_->bus = impl_->node.reader(Topic::bus_state);
  if (h.event && impl_->events == nullptr) impl_->events = impl_->node.reader(Topic::events);
  dds::WaitSet ws;
  for (dds::DataReader* r : {impl_->axis, impl_->bus, impl_->events}) {
    if (r == nullptr) continue;
    r->get_statuscondition().set_enabled_statuses(dds::StatusMask::data_available());
    ws.attach_condition(r->get_statuscondition());
  }
  dds::ConditionSeq active;
  ws.wait(active, eprosima::fastrtps::Duration_t(static_cast<double>(wait) * 1e-9));
  std::size_t n = 0;
  if (impl_->axis) n += take_all<msg::AxisState_>(impl_->axis, [&](const msg::AxisState_& m) { h.axis(to_sample(m)); });
  if (impl_->bus) n += take_all<msg::BusState_>(impl_->bus, [&](const msg::BusState_& m) { h.bus(to_sample(m)); });
  if (impl_->events) n += take_all<msg::Event_>(impl_->events, [&](const msg::Event_& m) { h.event(to_event(m)); });
  return n;
}

std::optional<control::ControlReply> TelemetryClient::call(const std::string& line, Nanos timeout) {
  if (impl_->requests == nullptr) {
    impl_->requests = impl_->node.writer(Topic::control_request);
    impl_->replies = impl_->node.reader(Topic::control_reply);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::nanoseconds(timeout);
  // A request written before a vdrive's reader matched would be lost (volatile): wait for both
  // ends of the exchange to be matched first.
  for (;;) {
    dds::PublicationMatchedStatus pub;
    dds::SubscriptionMatchedStatus sub;
    impl_->requests->get_publication_matched_status(pub);
    impl_->replies->get_subscription_matched_status(sub);
    if (pub.current_count > 0 && sub.current_count > 0) break;
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  msg::ControlRequest_ m;
  m.client(impl_->client);
  m.request_id(impl_->next_id++);
  m.request(line);
  impl_->requests->write(&m);
  for (;;) {
    msg::ControlReply_ r;
    dds::SampleInfo info;
    while (impl_->replies->take_next_sample(&r, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data && r.client() == m.client() && r.request_id() == m.request_id()) return control::parse_reply(r.reply());
    }
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace vdrive::telemetry
