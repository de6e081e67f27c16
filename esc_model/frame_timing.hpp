#pragma once
// When a frame passes an ESC, in the segment's global time (the Clock). The DC unit turns these
// into its local time when the master latches receive times (write to 0x0900).
//
// A frame enters at port 0 and is processed there; it then leaves through the ports in the
// ESC's order 0 -> 3 -> 1 -> 2 -> 0. Port N's time is when the frame comes back into port N
// from the cable (the subtree) behind it, so a master reading 0x0900-0x090F sees, port by port,
// how long each branch took. A port the frame does not leave through (closed, no link, not
// implemented) has no time: -1. A port whose cable leads out of this process (the line goes on in
// another process or on real slaves beyond a second interface) has its time only once the frame
// comes back: kLater, and Esc::frame_returned() supplies it.
#include "common/clock.hpp"

namespace vdrive::esc {

struct FrameTiming {
  // The frame left through this port and has not come back yet.
  static constexpr Nanos kLater = -2;

  Nanos port0_rx = 0;       // start of frame at port 0 (forward direction, processing happens here)
  Nanos port1_rx = -1;      // start of frame back at port 1; -1 when the frame does not leave there
  Nanos port2_rx = -1;
  Nanos port3_rx = -1;

  // A port's time by number (0..3), for code that walks the ports in order.
  Nanos& rx(int port) { return port == 0 ? port0_rx : port == 1 ? port1_rx : port == 2 ? port2_rx : port3_rx; }
};

}  // namespace vdrive::esc
