// The telemetry's sampling on the event loop thread. See sampler.hpp.
#include "vdrive/telemetry/sampler.hpp"


#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ethercat/registers.hpp"
#include "plant/plant.hpp"
#include "vdrive/control/run_fault_id.hpp"
#include "vdrive/fault/fault_injector.hpp"
#include "vdrive/network/network.hpp"
#include "vdrive/network/slave_lookup.hpp"
#include "vdrive/runtime/event_loop.hpp"

namespace vdrive::telemetry {
namespace {

constexpr std::uint16_t kAlStatus = ecat::reg::kAlStatus, kAlStatusCode = ecat::reg::kAlStatusCode;
constexpr std::size_t kMaxWatchedFaults = 64;

std::uint32_t sum_bytes(esc::Esc& e, std::uint16_t from, std::uint16_t to) {
  std::uint32_t s = 0;
  for (std::uint16_t a = from; a < to; ++a) s += e.peek(a);
  return s;
}

std::uint64_t load(const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); }

}  // namespace

const char* event_kind_name(EventKind kind) {
  switch (kind) {
    case EventKind::al_state: return "al_state";
    case EventKind::alarm_raised: return "alarm_raised";
    case EventKind::alarm_cleared: return "alarm_cleared";
    case EventKind::fault_injected: return "fault_injected";
    case EventKind::fault_cleared: return "fault_cleared";
    case EventKind::plant_set: return "plant_set";
    case EventKind::signal: return "signal";
    case EventKind::host_stall: return "host_stall";
  }
  return "unknown";
}

Sampler::Sampler(network::Network& network, double rate_hz, SamplerSources sources)
    : network_(network), sources_(sources),
      samples_(std::make_unique<runtime::SpscQueue<Sample, kQueueSize>>()) {
  if (!(rate_hz > 0.0 && rate_hz <= kMaxRateHz))
    throw std::invalid_argument(fmt::format("telemetry rate {} Hz is not in (0, {}] Hz", rate_hz, kMaxRateHz));
  period_ = std::max<Nanos>(1, std::llround(1e9 / rate_hz));
  for (std::size_t i = 0; i < network_.size(); ++i) {
    if (network_.firmware(i).drive() != nullptr) {
      od::ObjectStore& o = network_.firmware(i).objects();
      drives_.push_back(Drive{{o, 0x6041}, {o, 0x6040}, {o, 0x6061}, {o, 0x6064}, {o, 0x606C}, {o, 0x6077}, {o, 0x60F4}, {o, 0x603F},
                             {o, 0x607A}, {o, 0x60FD}, {o, 0x60B9}, {o, 0x60BA}});
      last_error_.push_back(static_cast<std::uint16_t>(drives_.back()->error_code.get()));
    } else {
      drives_.emplace_back();
      last_error_.push_back(0);
    }
    last_al_.push_back(network_.esc(i).peek_u16(kAlStatus));
  }
  last_faults_.reserve(kMaxWatchedFaults);
  if (sources_.counters != nullptr) stalls_seen_ = sources_.counters->stalls.count();  // earlier ones are no news
  for (std::size_t i = 0; i < network_.signals().size(); ++i) {
    const network::NamedSignal& sig = network_.signals()[i];
    signal_labels_.push_back(fmt::format("{} ({})", sig.name, network_.format_point(sig.point)));
    last_signals_.push_back(network_.signal(i).read());
  }
}

Sampler::~Sampler() = default;

void Sampler::poll(Nanos now) {
  if (!requests_.empty()) {
    while (std::optional<TelemetryRequest> r = requests_.try_pop()) {
      TelemetryReply reply{r->ticket, handle(*r, now)};
      // The telemetry thread drains replies as it drains samples; if it is that far behind,
      // its requester has given up waiting.
      (void)replies_.try_push(std::move(reply));
    }
  }
  if (now < next_) return;
  sample(now);
  next_ += period_;
  if (next_ <= now) next_ = now + period_;  // late by more than a period: skip, never burst
}

void Sampler::push(const Sample& s) {
  Sample copy = s;
  if (!samples_->try_push(std::move(copy))) dropped_.store(dropped_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}

void Sampler::event(Nanos now, std::uint16_t slave, EventKind kind, std::uint32_t value, std::uint32_t previous, const char* text) {
  EventSample e;
  e.time = now;
  e.slave = slave;
  e.kind = kind;
  e.value = value;
  e.previous = previous;
  const auto r = fmt::format_to_n(e.text.data(), e.text.size() - 1, "{}", text);
  *r.out = '\0';
  push(e);
}

void Sampler::sample(Nanos now) {
  const TurnaroundPeriod t = sources_.turnaround != nullptr ? sources_.turnaround->take() : TurnaroundPeriod{};
  sample_stalls();
  // A fault seen now that follows a host stall says so (the text, fixed size: no allocation).
  const RecentStall stall(sources_.counters, now);
  for (std::size_t i = 0; i < network_.size(); ++i) {
    esc::Esc& e = network_.esc(i);
    const std::uint16_t slave = line_slave(i);
    const std::uint16_t al = e.peek_u16(kAlStatus), code = e.peek_u16(kAlStatusCode);
    const std::uint16_t station = e.peek_u16(ecat::reg::kStationAddress);
    if (al != last_al_[i]) {
      char text[96];
      *fmt::format_to_n(text, sizeof text - 1, "AL status 0x{:02X} -> 0x{:02X}, status code 0x{:04X}{}", last_al_[i], al, code,
                        (al & ecat::reg::kAlErrorFlag) != 0 ? stall.text() : "").out = '\0';
      event(now, slave, EventKind::al_state, al, last_al_[i], text);
      last_al_[i] = al;
    }
    if (drives_[i]) {
      const Drive& d = *drives_[i];
      AxisSample a;
      a.time = now;
      a.slave = slave;
      a.station = station;
      a.al_state = al;
      a.al_status_code = code;
      a.statusword = static_cast<std::uint16_t>(d.statusword.get());
      a.controlword = static_cast<std::uint16_t>(d.controlword.get());
      a.mode = static_cast<std::int8_t>(d.mode.get());
      a.position = static_cast<std::int32_t>(d.position.get());
      a.velocity = static_cast<std::int32_t>(d.velocity.get());
      a.torque = static_cast<std::int16_t>(d.torque.get());
      a.following_error = static_cast<std::int32_t>(d.following_error.get());
      a.error_code = static_cast<std::uint16_t>(d.error_code.get());
      a.target_position = static_cast<std::int32_t>(d.target_position.get());
      a.digital_inputs = static_cast<std::uint32_t>(d.digital_inputs.get());
      a.probe_status = static_cast<std::uint16_t>(d.probe_status.get());
      a.probe_position1 = static_cast<std::int32_t>(d.probe_position1.get());
      a.winding_c = a.housing_c = std::numeric_limits<double>::quiet_NaN();
      if (const plant::Plant* p = network_.firmware(i).plant(); p != nullptr && p->axis_count() > 0) {
        a.winding_c = p->feedback(0).winding_c;
        a.housing_c = p->feedback(0).housing_c;
      }
      push(a);
      if (a.error_code != last_error_[i]) {
        char text[96];
        *fmt::format_to_n(text, sizeof text - 1, "603Fh 0x{:04X} -> 0x{:04X}{}", last_error_[i], a.error_code,
                          a.error_code != 0 ? stall.text() : "").out = '\0';
        event(now, slave, a.error_code != 0 ? EventKind::alarm_raised : EventKind::alarm_cleared, a.error_code, last_error_[i], text);
        last_error_[i] = a.error_code;
      }
    }
    BusSample b;
    b.time = now;
    b.slave = slave;
    b.station = station;
    b.al_state = al;
    b.al_status_code = code;
    if (sources_.counters != nullptr) {
      b.frames_in = load(sources_.counters->frames_in);
      b.frames_out = load(sources_.counters->frames_out);
      b.frames_dropped = load(sources_.counters->dropped);
      b.send_failed = load(sources_.counters->send_failed);
    }
    b.rx_errors = sum_bytes(e, ecat::reg::kRxErrorCounter, ecat::reg::kRxErrorCounter + 8);
    b.lost_links = sum_bytes(e, ecat::reg::kLostLinkCounter, ecat::reg::kLostLinkCounterEnd);
    b.samples_dropped = dropped();
    b.turnaround_last = t.last;
    b.turnaround_min = t.min;
    b.turnaround_mean = t.mean;
    b.turnaround_max = t.max;
    if (sources_.counters != nullptr) {
      b.host_stalls = sources_.counters->stalls.count();
      b.longest_host_stall = sources_.counters->stalls.longest();
    }
    push(b);
  }
  if (sources_.faults != nullptr) sample_faults(now);
  sample_signals(now);
}

// Each host stall the loop recorded since the last sample is an event at the time the loop ran
// again: value its length and previous the threshold, in microseconds; the text says what the
// drives saw (runtime::describe). On the loop thread, so the ring is read as it was written.
void Sampler::sample_stalls() {
  if (sources_.counters == nullptr) return;
  const runtime::HostStalls& stalls = sources_.counters->stalls;
  for (const std::uint64_t count = stalls.count(); stalls_seen_ < count;) {
    const std::optional<runtime::HostStall> s = stalls.get(++stalls_seen_);
    if (!s) continue;  // more stalls in one period than the ring holds: the counter has them
    EventSample e;
    e.time = s->time;
    e.kind = EventKind::host_stall;
    e.value = static_cast<std::uint32_t>(std::min<Nanos>(s->length / 1000, UINT32_MAX));
    e.previous = static_cast<std::uint32_t>(std::min<Nanos>(s->threshold / 1000, UINT32_MAX));
    runtime::describe(*s, e.text, place_.slaves_before);
    push(e);
  }
}

Sampler::RecentStall::RecentStall(const runtime::LoopCounters* counters, Nanos now) {
  const std::optional<runtime::HostStall> s = counters != nullptr ? counters->stalls.just_before(now) : std::nullopt;
  if (s) *fmt::format_to_n(text_.data(), text_.size() - 1, " after a host stall of {:.1f} ms", static_cast<double>(s->length) / 1e6).out = '\0';
}

// A named signal's change is an event (value and previous truncated to 32 bits; the text has
// them whole), so a subscriber sees a door open or a switch close without polling.
void Sampler::sample_signals(Nanos now) {
  for (std::size_t i = 0; i < last_signals_.size(); ++i) {
    const std::int64_t v = network_.signal(i).read();
    if (v == last_signals_[i]) continue;
    char text[96];
    *fmt::format_to_n(text, sizeof text - 1, "{} {} -> {}", signal_labels_[i], last_signals_[i], v).out = '\0';
    event(now, line_slave(network_.signals()[i].point.slave), EventKind::signal,
          static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(last_signals_[i]), text);
    last_signals_[i] = v;
  }
}

int Sampler::run_id(int id) const { return control::run_fault_id(place_.part, id, place_.parts); }

void Sampler::sample_faults(Nanos now) {
  const std::vector<fault::ActiveFault>& active = sources_.faults->active();
  for (const fault::ActiveFault& f : active) {
    if (std::find(last_faults_.begin(), last_faults_.end(), f.id) != last_faults_.end()) continue;
    char text[80];
    *fmt::format_to_n(text, sizeof text - 1, "fault {} {} started", run_id(f.id), fault::info(f.spec.kind).name).out = '\0';
    const std::uint16_t slave = f.spec.slave > 0 ? line_slave(static_cast<std::size_t>(f.spec.slave) - 1) : 0;
    event(now, slave, EventKind::fault_injected, static_cast<std::uint32_t>(run_id(f.id)), 0, text);
  }
  for (const int id : last_faults_) {
    if (std::any_of(active.begin(), active.end(), [id](const fault::ActiveFault& f) { return f.id == id; })) continue;
    char text[48];
    *fmt::format_to_n(text, sizeof text - 1, "fault {} ended", run_id(id)).out = '\0';
    event(now, 0, EventKind::fault_cleared, static_cast<std::uint32_t>(run_id(id)), 0, text);
  }
  last_faults_.clear();  // keeps its capacity
  for (const fault::ActiveFault& f : active)
    if (last_faults_.size() < kMaxWatchedFaults) last_faults_.push_back(f.id);
}

control::ControlReply Sampler::handle(const TelemetryRequest& r, Nanos now) {
  if (r.kind == TelemetryRequest::Kind::fault) {
    if (!fault_handler_) return control::error_reply(control::ControlReply::Status::failed, "this vdrive takes no fault requests");
    return fault_handler_(r.fault, now);
  }
  const PlantSet& p = r.plant;
  const std::size_t own = network_.size() + place_.slaves_before;
  if (p.slave > 0 && static_cast<std::size_t>(p.slave) > own && static_cast<std::size_t>(p.slave) <= own + place_.slaves_after)
    return control::error_reply(control::ControlReply::Status::bad_request,
                                fmt::format("plant_set: slave {} is served by another process of this run (vdrive run --processes); "
                                            "plant changes reach slaves {}-{} only", p.slave, place_.slaves_before + 1, own));
  std::size_t index = 0;
  try {
    const ecat::SlaveRef ref = p.station != 0 ? ecat::SlaveRef{ecat::SlaveRef::Kind::address, p.station}
                                              : ecat::SlaveRef{ecat::SlaveRef::Kind::position, static_cast<std::uint16_t>(p.slave)};
    index = network::find_slave(network_, ref);
  } catch (const std::invalid_argument& e) {
    return control::error_reply(control::ControlReply::Status::bad_request, fmt::format("plant_set: {}", e.what()));
  }
  plant::Plant* plant = network_.firmware(index).plant();
  if (plant == nullptr || plant->axis_count() == 0)
    return control::error_reply(control::ControlReply::Status::bad_request, fmt::format("plant_set: slave {} has no plant", index + 1));
  plant->set_external_load(0, p.external_load);
  char text[64];
  *fmt::format_to_n(text, sizeof text - 1, "external load {:g}", p.external_load).out = '\0';
  event(now, line_slave(index), EventKind::plant_set, 0, 0, text);
  return {};
}

}  // namespace vdrive::telemetry
