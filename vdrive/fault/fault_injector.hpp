#pragma once
// FaultInjector: starts and ends faults (fault_spec.hpp) on a running network, one layer each:
// the wire (WireImpairment between the master and the line, cable breaks in the Segment), the
// ESC (esc::EscFaults), the mailbox (MailboxFaults, one-shot), the drive (DriveEngine injected
// causes and alarms) and the plant (plant::AxisFaults). Several faults of one layer combine:
// drop probabilities as independent losses, the longest delay, ESC/plant switches ORed.
//
// Faults end when their duration runs out (tick()), when cleared, or never. What follows is the
// product's reaction, which the layers below produce; nothing here scripts it.
// Single-threaded: call on the thread that owns the network. start/clear allocate; tick() does not
// unless a fault ends.
#include <stdexcept>
#include <vector>

#include "common/clock.hpp"
#include "vdrive/fault/fault_spec.hpp"

namespace vdrive::network { class Network; }

namespace vdrive::fault {

class WireImpairment;

// A fault that cannot act here: no such slave, no drive, an alarm the product does not have, a
// wire fault without a wire stage. The message names the fault and what was wrong.
class FaultError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct ActiveFault {
  int id = 0;
  FaultSpec spec;
  Nanos started = 0;
  Nanos ends = 0;  // INT64_MAX: until cleared
};

class FaultInjector {
public:
  // `wire` may be null (e.g. a real interface without an impairment stage): wire faults other
  // than link_down are then refused.
  FaultInjector(network::Network& network, WireImpairment* wire);

  // Starts `spec` now; returns its id (1, 2, ...). One-shot faults act and are not kept. A slave
  // named by its station address is found now, among the addresses the master has set.
  int inject(const FaultSpec& spec, Nanos now);
  // Ends fault `id`; false if no such fault is active.
  bool clear(int id, Nanos now);
  void clear_all(Nanos now);
  // Ends the faults whose duration ran out by `now`.
  void tick(Nanos now);
  Nanos next_deadline() const;  // INT64_MAX when nothing ends by itself

  const std::vector<ActiveFault>& active() const { return active_; }

  // The slaves after this network's last that other processes of the same run serve (`vdrive run
  // --processes`): a fault for one of them is refused saying so, not as a slave the line lacks.
  // Part 1's control socket routes such faults to their part first (control/part_router.hpp), so
  // this refusal is what the front ends that act on part 1 alone (web page, DDS) answer.
  void set_later_slaves(std::size_t count) { later_slaves_ = count; }

private:
  // The refusal of slave `slave` (from 1), beyond this network's: in a later part, or none.
  [[noreturn]] void refuse_slave(const FaultSpec& spec, int slave) const;
  FaultSpec with_position(const FaultSpec& spec) const;
  void check(const FaultSpec& spec) const;
  void apply_one_shot(const FaultSpec& spec, Nanos now);
  void set_drive_cause(const FaultSpec& spec, bool active, Nanos now);
  // After `spec` started or ended: its layer's settings from the faults now active.
  void apply_layer(const FaultSpec& spec, bool started, Nanos now);
  // Recomputes a layer's settings from the faults still active.
  void apply_wire();
  void apply_cables();
  void apply_esc(int slave);
  void apply_plant(int slave);
  void end(std::size_t index, Nanos now);

  network::Network& network_;
  WireImpairment* wire_;
  std::vector<ActiveFault> active_;
  int next_id_ = 1;
  std::size_t later_slaves_ = 0;
};

}  // namespace vdrive::fault
