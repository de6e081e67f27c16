// Runtime fault control on the event loop's thread. See fault_service.hpp.
#include "vdrive/control/fault_service.hpp"

#include <fmt/core.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "common/clock.hpp"
#include "vdrive/control/signal_requests.hpp"
#include "vdrive/runtime/line_status.hpp"
#include "vdrive/fault/impaired_link.hpp"
#include "vdrive/network/slave_lookup.hpp"

namespace vdrive::control {
namespace {
constexpr Nanos kNever = std::numeric_limits<Nanos>::max();
}

FaultService::FaultService(network::Network& network, fault::WireImpairment* wire, fault::ImpairedLink* link)
    : network_(network), injector_(network, wire), link_(link) {
  reply_event_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (reply_event_ < 0) throw std::runtime_error(fmt::format("eventfd: {}", std::strerror(errno)));
}

FaultService::~FaultService() { ::close(reply_event_); }

void FaultService::changed() {
  if (link_ != nullptr) link_->refresh();
}

void FaultService::poll(Nanos now) {
  if (!requests_.empty()) {
    while (std::optional<ControlRequest> r = requests_.try_pop()) {
      ControlReply reply = handle(*r, now);
      reply.seq = r->seq;
      // The caller waits for one reply at a time, so there is room; if not, it timed out and
      // no longer waits for this one.
      (void)replies_.try_push(std::move(reply));
      const std::uint64_t one = 1;
      (void)!::write(reply_event_, &one, sizeof one);
    }
  }
  if (next_armed() <= now) inject_armed(now);
  if (injector_.next_deadline() <= now) {
    // Logged here, before tick() forgets them: an ending is as much news as the injection was.
    for (const fault::ActiveFault& f : injector_.active())
      if (f.ends <= now) spdlog::info("fault {} ended: its duration ran out ({})", f.id, fault::describe(f.spec));
    injector_.tick(now);
    changed();
  }
}

void FaultService::arm(const fault::FaultSpec& spec, Nanos at, std::string origin) {
  const auto pos = std::upper_bound(armed_.begin(), armed_.end(), at, [](Nanos t, const Armed& a) { return t < a.at; });
  armed_.insert(pos, Armed{spec, at, std::move(origin)});
}

Nanos FaultService::next_armed() const { return armed_done_ < armed_.size() ? armed_[armed_done_].at : kNever; }

void FaultService::inject_armed(Nanos now) {
  while (armed_done_ < armed_.size() && armed_[armed_done_].at <= now) {
    const Armed& a = armed_[armed_done_++];
    ControlRequest r;
    r.op = ControlRequest::Op::inject;
    r.fault = a.spec;
    const ControlReply reply = handle(r, now);
    if (!reply.ok()) spdlog::warn("{}: armed fault not injected: {}", a.origin, reply.error);
    else spdlog::info("{}: armed fault {} ({})", a.origin, reply.id, fault::describe(a.spec));
  }
}

ControlReply FaultService::handle(const ControlRequest& r, Nanos now) {
  if (r.op == ControlRequest::Op::signal_get || r.op == ControlRequest::Op::signal_set ||
      r.op == ControlRequest::Op::signals)
    return handle_signal_request(network_, r);
  ControlReply reply;
  try {
    switch (r.op) {
      case ControlRequest::Op::inject:
        reply.id = injector_.inject(r.fault, now);
        if (fault::info(r.fault.kind).one_shot) reply.id = 0;
        if (reply.id == 0) spdlog::info("one-shot fault applied: {}", fault::describe(r.fault));
        else spdlog::info("fault {} injected: {}", reply.id, fault::describe(r.fault));
        break;
      case ControlRequest::Op::clear:
        if (!injector_.clear(r.id, now))
          return error_reply(ControlReply::Status::bad_request, fmt::format("no active fault {}", r.id));
        spdlog::info("fault {} cleared", r.id);
        break;
      case ControlRequest::Op::clear_all:
        reply.cleared = static_cast<int>(injector_.active().size());
        injector_.clear_all(now);
        spdlog::info("all faults cleared ({})", reply.cleared);
        break;
      case ControlRequest::Op::signal_get:
      case ControlRequest::Op::signal_set:
      case ControlRequest::Op::signals:
        break;  // above
      case ControlRequest::Op::find_station:
        try {
          reply.slave = static_cast<int>(network::find_slave(network_, {ecat::SlaveRef::Kind::address, r.station})) + 1;
        } catch (const std::invalid_argument& e) {
          return error_reply(ControlReply::Status::bad_request, e.what());
        }
        return reply;  // nothing changed
      case ControlRequest::Op::line_status:
        for (std::size_t i = 0; i < network_.size(); ++i) {
          const runtime::SlaveStatus st = runtime::slave_status(network_, i);
          reply.states.push_back({st.al_status, st.al_status_code, st.rx_errors});
        }
        return reply;  // nothing changed
      case ControlRequest::Op::list:
        for (const fault::ActiveFault& f : injector_.active()) {
          reply.faults.push_back({f.id, std::string(fault::info(f.spec.kind).name), fault::describe(f.spec),
                                  now - f.started, f.ends == kNever ? -1 : std::max<Nanos>(f.ends - now, 0)});
        }
        break;
    }
  } catch (const fault::FaultError& e) {
    reply = error_reply(ControlReply::Status::bad_request, e.what());
  } catch (const std::exception& e) {
    reply = error_reply(ControlReply::Status::failed, e.what());
  }
  changed();
  return reply;
}

ControlReply FaultService::call(ControlRequest request, Nanos timeout) {
  const std::lock_guard<std::mutex> turn(callers_);
  const std::uint64_t seq = next_seq_++;
  request.seq = seq;
  if (!requests_.try_push(std::move(request)))
    return error_reply(ControlReply::Status::failed, "the event loop has too many requests pending");
  if (wake_) wake_();
  MonotonicClock clock;
  const Nanos deadline = clock.now() + timeout;
  for (;;) {
    while (std::optional<ControlReply> reply = replies_.try_pop()) {
      if (reply->seq == seq) return std::move(*reply);  // older ones: their caller gave up
    }
    const Nanos left = deadline - clock.now();
    if (left <= 0) {
      return error_reply(ControlReply::Status::failed,
                         fmt::format("the event loop did not answer within {} ms", timeout / 1'000'000));
    }
    pollfd p{reply_event_, POLLIN, 0};
    ::poll(&p, 1, static_cast<int>(std::max<Nanos>(left / 1'000'000, 1)));
    std::uint64_t count = 0;
    (void)!::read(reply_event_, &count, sizeof count);
  }
}

}  // namespace vdrive::control
