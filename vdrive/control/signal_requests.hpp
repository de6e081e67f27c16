#pragma once
// Signals of a served network read and set through the control socket, on the loop's thread: a
// request names a signal of the network file (`signals:`) or a point ("di 0x6000:1", "x.home",
// network/signal_point.hpp). A name or point that does not exist, or a value the point cannot
// hold, is a bad_request naming it; a value set on a wire's target lasts until the wire's next copy.
#include "vdrive/control/control_request.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::control {

// For Op::signal_get, signal_set and signals.
ControlReply handle_signal_request(network::Network& network, const ControlRequest& request);

}  // namespace vdrive::control
