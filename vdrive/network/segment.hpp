#pragma once
// The line of slaves on one link, as on a real cable: a frame enters slave 1 at port 0, is
// processed there, leaves port 1 to slave 2, ... and the last open port loops it back through
// every slave's port 1 -> port 0 path to the master. Each hop adds a configurable delay, which the
// DC receive times reflect:
//   slave i (0-based) sees the frame at port 0 at rx_time + i * hop_delay;
//   if slave k is where the frame turns (last slave, or port 1 not forwarding: closed by DL
//   control 0x0100 or no link), slave i < k sees it again at port 1 at rx_time + (2k - i) * hop.
// The turning point is decided before the frame is processed, as the silicon forwards a frame
// while still receiving it (a DL control write in this frame acts on the next one).
// On the way back the first slave sets bit 1 of the source MAC's first byte (0x02), as ESCs do.
//
// Ethernet: destination and source MAC, EtherType 0x88A4, optionally behind one 802.1Q tag.
// Non-EtherCAT frames, frames an ESC destroys (malformed), and frames that meet a cut cable
// before slave 1 do not come back. Allocates nothing per frame; single-threaded.
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
  Nanos hop_delay() const { return hop_delay_; }

  // Cable break between slave i and i+1 (i = -1: between master and slave 1). Updates port
  // links on both sides (Esc::set_links). Out-of-range positions are ignored.
  void set_cable(int after_slave, bool connected);
  bool cable_connected(int after_slave) const;

  // Processes one Ethernet frame in place as the line would; `rx_time` is when the master's frame
  // reached slave 1. Returns true if the frame comes back to the master (then send it), false if
  // it was destroyed (malformed, or the line is cut before slave 1). Non-EtherCAT frames: false.
  // Allocates nothing.
  bool process(std::span<std::uint8_t> ethernet_frame, Nanos rx_time);

  // A frame that left the master with a wrong FCS (corrupted on the cable into slave 1, see
  // fault::WireImpairment): its content does not matter, as no ESC executes it. As the silicon
  // does, slave 1 counts an invalid frame at port 0 (0x0300) and forwards it marked; every other
  // slave it passes counts a forwarded RX error (0x0308 at port 0 on the way out, 0x0309 at
  // port 1 on the way back). It never comes back to the master (its NIC drops a bad FCS); it
  // counts in dropped(). A cable cut before slave 1: nobody sees it. Any frame counts (the FCS
  // is checked before the EtherType matters); its bytes and time change nothing. Allocates nothing.
  void process_corrupted(std::span<const std::uint8_t> ethernet_frame, Nanos rx_time);

  // Frames that did not come back (not EtherCAT, destroyed by an ESC, line cut at slave 1).
  std::uint64_t dropped() const { return dropped_; }

private:
  void update_links();
  std::size_t turning_slave() const;
  Nanos hop_delay_;
  std::vector<esc::Esc*> slaves_;
  std::vector<std::uint8_t> cable_ok_;  // cable_ok_[i] != 0: cable into slave i (from master or slave i-1)
  std::uint64_t dropped_ = 0;
};

}  // namespace vdrive::network
