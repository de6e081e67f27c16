#pragma once
// The line of slaves on one link, as on a real cable: a frame enters slave 1 at port 0, is
// processed there, leaves port 1 to slave 2, ... and the last open port loops it back through
// every slave's port 1 -> port 0 path to the master. Each hop adds a configurable delay, which the
// DC receive times reflect. A port closed by DL control (0x0100) or a broken cable loops the frame
// back early; slaves behind it do not see it.
#include <cstdint>
#include <span>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"

namespace vdrive::network {

class Segment {
public:
  explicit Segment(Nanos hop_delay = 500);  // ns per slave, each direction (cable + ESC forwarding)

  void append(esc::Esc& esc);   // slaves in cable order; call before the first frame
  std::size_t size() const { return slaves_.size(); }
  esc::Esc& slave(std::size_t i) { return *slaves_[i]; }

  // Cable break between slave i and i+1 (i = -1: between master and slave 1). Updates port links.
  void set_cable(int after_slave, bool connected);

  // Processes one Ethernet frame in place as the line would; `rx_time` is when the master's frame
  // reached slave 1. Returns true if the frame comes back to the master (then send it), false if
  // it was destroyed (malformed, or the line is cut before slave 1). Non-EtherCAT frames: false.
  // Allocates nothing.
  bool process(std::span<std::uint8_t> ethernet_frame, Nanos rx_time);

private:
  void update_links();
  Nanos hop_delay_;
  std::vector<esc::Esc*> slaves_;
  std::vector<bool> cable_ok_;   // cable_ok_[i]: cable into slave i (from master or slave i-1)
};

}  // namespace vdrive::network
