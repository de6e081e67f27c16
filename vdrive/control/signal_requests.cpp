#include "vdrive/control/signal_requests.hpp"

#include <fmt/core.h>

#include <stdexcept>

namespace vdrive::control {
namespace {

struct Found {
  SignalStatus status;
  network::SignalAccess access;
};

Found find(network::Network& net, const std::string& signal) {
  const network::SignalPoint point = net.point_of(signal);
  const network::SignalAccess access = net.resolve(point);
  return {{signal, net.format_point(point), access.type_name()}, access};
}

}  // namespace

ControlReply handle_signal_request(network::Network& net, const ControlRequest& r) {
  ControlReply reply;
  try {
    if (r.op == ControlRequest::Op::signals) {
      for (std::size_t i = 0; i < net.signals().size(); ++i) {
        const network::NamedSignal& s = net.signals()[i];
        reply.signals.push_back({s.name, net.format_point(s.point), net.signal(i).type_name(), net.signal(i).read()});
      }
      return reply;
    }
    Found f = find(net, r.signal);
    if (r.op == ControlRequest::Op::signal_set) f.access.write(r.value);
    f.status.value = f.access.read();
    reply.signals.push_back(std::move(f.status));
  } catch (const std::invalid_argument& e) {
    return error_reply(ControlReply::Status::bad_request, e.what());
  } catch (const std::out_of_range& e) {
    return error_reply(ControlReply::Status::bad_request, fmt::format("signal '{}': {}", r.signal, e.what()));
  }
  return reply;
}

}  // namespace vdrive::control
