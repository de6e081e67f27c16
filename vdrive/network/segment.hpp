#pragma once
// The slaves on one link, cabled as a tree as on real EtherCAT (topology.hpp; by default the
// line: slave i's port 1 to slave i+1's port 0). A frame enters the root slave at port 0 and is
// processed there; each ESC then sends it out of its ports in the order 0 -> 3 -> 1 -> 2 -> 0
// (ETG.1000.4, ESC datasheets "frame processing order"): out of port 3 into the subtree cabled
// there, back in at port 3, out of port 1, and so on, and finally out of port 0 back towards the
// master. A port that does not forward (not implemented, no link, closed by DL control 0x0100)
// is looped back inside the ESC and skipped. So every ESC processes the frame once, on its port-0
// arrival, depth first; the master's auto-increment positions count ESCs in that order.
//
// Timing: each hop (cable plus forwarding) adds the configurable hop delay, either direction.
// An ESC sees the frame at port 0 when it arrives; at port N when it comes back from the
// subtree behind port N (esc::FrameTiming), which the DC receive time latch (0x0900) reports.
// In the line, slave i sees the frame at port 0 at rx_time + i * hop; if slave k is where the
// frame turns, slave i < k sees it again at port 1 at rx_time + (2k - i) * hop.
// The whole path is decided before the frame is processed, as the silicon forwards a frame while
// still receiving it (a DL control write in this frame acts on the next one).
// On the way back the root slave sets bit 1 of the source MAC's first byte (0x02), as ESCs do.
//
// The onward port (set_onward_port): the line may go on beyond this process, out of port 1 of the
// last slave a frame visits, to slaves served elsewhere (another vdrive on a second interface, or
// real slaves on a NIC), as one line is spread over many devices. A frame that reaches that port
// while it forwards (link up, not closed by DL control) leaves onward (route() says so) once this
// process's slaves have processed it; it comes back later through the same port (returned()),
// and only then does it pass the ports on its way back to the master, which latch its DC receive
// times then (FrameTiming::kLater). With the onward link down the last slave closes the port and
// the frame turns there, as the silicon's loop control does.
//
// Ethernet: destination and source MAC, EtherType 0x88A4, optionally behind one 802.1Q tag.
// Non-EtherCAT frames, frames an ESC destroys (malformed), and frames that meet a cut cable
// before the root slave do not come back. Allocates nothing per frame; single-threaded.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "esc_model/frame_timing.hpp"
#include "vdrive/network/topology.hpp"

namespace vdrive::network {

// Where a frame goes once this process's slaves have processed it.
enum class FrameExit : std::uint8_t {
  Destroyed,  // malformed, not EtherCAT, or the cable into the root is cut: nothing goes out
  ToMaster,   // back out of the root's port 0
  Onward,     // out of the onward port, to the rest of the line (set_onward_port)
};

class Segment {
public:
  explicit Segment(Nanos hop_delay = 500);  // ns per hop, each direction (cable + ESC forwarding)

  // Slaves in the order they are numbered (0-based); call before set_topology and before the
  // first frame. Appending makes the topology the line again.
  void append(esc::Esc& esc);
  std::size_t size() const { return slaves_.size(); }
  esc::Esc& slave(std::size_t i) { return *slaves_[i]; }
  Nanos hop_delay() const { return hop_delay_; }

  // Cables the appended slaves as `topology` says (empty: the line), all cables connected.
  // Throws std::invalid_argument (validate()) for a topology that cannot be cabled with these
  // ESCs' ports.
  void set_topology(const Topology& topology);
  // Where slave i's port 0 is cabled (the line spelled out if no topology was set).
  const Uplink& uplink(std::size_t slave) const { return uplinks_[slave]; }
  // The slave whose port 0 is cabled to port `port` of `slave`, or -1 if none; for port 0, the
  // slave itself (its own way in).
  int cabled_at(std::size_t slave, int port) const;

  // Cables are named by the slave they lead into (port 0 side): the cable into slave i comes from
  // the master or from a port of its parent. A broken cable takes both ends' links down
  // (Esc::set_links); the ESC on the parent side closes that port (auto loop control) and turns
  // the frame there, so the subtree behind it sees nothing.
  //
  // The line's numbering, kept for it: the cable into slave after_slave + 1 (in the line, the one
  // between slave after_slave and the next; -1: from the master into slave 0). Out-of-range
  // positions are ignored.
  void set_cable(int after_slave, bool connected);
  bool cable_connected(int after_slave) const;
  // The cable at port `port` (0..3) of `slave`: port 0 is the cable into it, ports 1..3 those
  // to the slaves behind it. Returns false (and changes nothing) if nothing is cabled there.
  bool set_port_cable(std::size_t slave, int port, bool connected);
  bool port_cable_connected(std::size_t slave, int port) const;

  // Processes one Ethernet frame in place as the cabled slaves would; `rx_time` is when the
  // master's frame reached the root slave. Returns where it goes: back to the master, onward, or
  // nowhere (malformed, not EtherCAT, the cable into the root cut). Allocates nothing.
  FrameExit route(std::span<std::uint8_t> ethernet_frame, Nanos rx_time);
  // route() for a segment without an onward port: true if the frame comes back to the master.
  bool process(std::span<std::uint8_t> ethernet_frame, Nanos rx_time) {
    return route(ethernet_frame, rx_time) != FrameExit::Destroyed;
  }

  // The onward port: port 1 of the last slave in visiting order (every cable connected) leads out
  // of this process. Throws std::invalid_argument if there are no slaves or that slave's ESC has
  // no port 1. The link starts down (set_onward_link).
  void set_onward_port();
  bool has_onward_port() const { return onward_slave_ >= 0; }
  // The slave whose port 1 is the onward port (0-based), or -1.
  int onward_slave() const { return onward_slave_; }
  // Link on the onward port (the second interface's carrier): its ESC's DL status and loop
  // control follow it.
  void set_onward_link(bool up);
  bool onward_link() const { return onward_link_; }
  // A frame that route() sent onward came back in through the onward port at `rx_time`: it passes
  // the ports on its way back to the master (their DC receive-time latches, if it wrote 0x0900),
  // and the root marks its source MAC. Returns false (send nothing) for a non-EtherCAT frame or
  // a segment without an onward port. Allocates nothing.
  bool returned(std::span<std::uint8_t> ethernet_frame, Nanos rx_time);

  // A frame that left the master with a wrong FCS (corrupted on the cable into the root, see
  // fault::WireImpairment): its content does not matter, as no ESC executes it. As the silicon
  // does, the root counts an invalid frame at port 0 (0x0300) and forwards it marked; every other
  // ESC counts a forwarded RX error (0x0308 + port) at port 0 on the way in and at each port the
  // frame comes back through. It never comes back to the master (its NIC drops a bad FCS); it
  // counts in dropped(). A cable cut before the root: nobody sees it. Any frame counts (the FCS
  // is checked before the EtherType matters); its bytes and time change nothing. Allocates nothing.
  void process_corrupted(std::span<const std::uint8_t> ethernet_frame, Nanos rx_time);

  // Frames that did not come back (not EtherCAT, destroyed by an ESC, cable into the root cut).
  std::uint64_t dropped() const { return dropped_; }

private:
  // One ESC on the way down the tree while a frame's path is planned: which of its downstream
  // ports (kDownstreamPortOrder) comes next.
  struct Walk {
    std::uint32_t slave;
    std::uint32_t next;
  };
  // A slave's cabled downstream ports in port order, so that a frame's walk looks only at ports
  // with a cable (in the line: one per slave).
  struct Branch {
    std::int32_t child;
    std::int32_t port;
  };
  struct Branches {
    std::array<Branch, 3> in_order;
    std::uint32_t count;
  };
  void cable(const Topology& topology);
  void update_links();
  // The frame's path and timing before any ESC processes it: fills order_ (the ESCs in visiting
  // order) and timings_ (per slave); returns how many ESCs the frame visits.
  // A frame that reaches the onward port while it forwards sets `onward` and ends the walk there
  // (the onward slave is the last one visited), its way back left to returned().
  std::size_t plan(Nanos rx_time, bool& onward);
  std::int32_t last_visited() const;  // with every cable connected
  // The line's walk needs only where the frame turns.
  std::size_t line_turn() const;

  Nanos hop_delay_;
  std::vector<esc::Esc*> slaves_;
  std::vector<std::uint8_t> cable_ok_;               // cable_ok_[i] != 0: the cable into slave i
  std::vector<Uplink> uplinks_;                      // per slave, the line filled in
  std::vector<std::array<std::int32_t, 4>> children_;  // children_[s][p]: slave on port p, or -1
  std::vector<Branches> branches_;                   // the same in port order 3, 1, 2
  std::int32_t root_ = -1;                           // the slave on the master's cable
  bool line_ = true;                                 // cabled as the line: the line's own walk
  std::int32_t onward_slave_ = -1;                   // set_onward_port()
  bool onward_link_ = false;
  // Per-frame scratch, sized when slaves are cabled so that frames allocate nothing.
  std::vector<esc::FrameTiming> timings_;
  std::vector<std::uint32_t> order_;
  std::vector<Walk> walk_;
  std::uint64_t dropped_ = 0;
};

}  // namespace vdrive::network
