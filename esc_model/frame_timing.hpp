#pragma once
// When a frame passes an ESC, in the segment's global time (the Clock). The DC unit turns these
// into its local time when the master latches receive times (write to 0x0900).
#include "common/clock.hpp"

namespace vdrive::esc {

struct FrameTiming {
  Nanos port0_rx = 0;       // start of frame at port 0 (forward direction, processing happens here)
  Nanos port1_rx = -1;      // start of frame at port 1 on its way back; -1 when port 1 is closed
  Nanos port2_rx = -1;      // ports 2/3: unused in a line, -1
  Nanos port3_rx = -1;
};

}  // namespace vdrive::esc
