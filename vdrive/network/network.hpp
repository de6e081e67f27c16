#pragma once
// Network: the slaves of one link, as the event loop drives them. For each slave (in the order
// given) it loads the product, a built-in or --profile-dir product id ("a6b") or a device of an ESI
// file ("EL1008.xml", "devices.xml:0x3F03052:0x110000", esi/esi_import.hpp), builds the ESC from it
// (identity registers, SII image) and the slave firmware, and cables the ESCs into a Segment as
// NetworkOptions::topology says (by default a line in that order); all are powered on at
// construction.
//
// Per frame: the segment processes it in place, then the firmware of every slave whose PDI IRQ
// is asserted is serviced (as a microcontroller's IRQ handler would run right after the frame).
// Timers: tick() runs the ESCs' time-based behaviour (SYNC, watchdogs) and firmware tasks that
// are due. Single-threaded; nothing allocates after construction.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/clock.hpp"
#include "esc_model/esc.hpp"
#include "vdrive/firmware/slave_firmware.hpp"
#include "vdrive/network/between_slaves.hpp"
#include "vdrive/network/segment.hpp"
#include "vdrive/network/signal_access.hpp"
#include "vdrive/network/signal_wire.hpp"
#include "vdrive/network/topology.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::network {

// The DC oscillator of one slave's ESC (esc::DcUnit): drift in ppm, local time at global time 0.
struct DcModel {
  double drift_ppm = 0.0;
  Nanos start_offset = 0;
};

struct IdentityChoice {
  std::uint32_t product_code = 0;
  std::uint32_t revision = 0;
};

struct NetworkOptions {
  Nanos hop_delay = 500;     // ns per hop and direction, see Segment
  std::string profile_dir;   // empty: the profiles built into the binary
  std::vector<DcModel> dc_models = {};  // per slave in the order given; slaves beyond it: ideal oscillator
  // Per slave in the order given: the machine its drive moves; absent/empty = the product's default plant.
  std::vector<std::optional<plant::PlantDescription>> plants = {};
  // Per slave in the order given: the configured station alias its EEPROM holds (SII word 4, loaded
  // into 0x0012 at power-on); absent: the product's (usually 0).
  std::vector<std::optional<std::uint16_t>> station_aliases = {};
  // Per slave in the order given: the product code and revision a built-in product is served with,
  // where it covers several (Identity::product_code_mask, e.g. an ENI's A6B model); absent: its own.
  std::vector<std::optional<IdentityChoice>> identities = {};
  // Wires between signal points (signal_wire.hpp).
  std::vector<SignalWire> wires = {};
  // Named signal points (a network file's `signals:`), for the control socket, scenarios and telemetry.
  std::vector<NamedSignal> signals = {};
  // Per slave in the order given: its name in signal points ("di 0x6000:1"); absent: its position.
  std::vector<std::string> slave_names = {};
  // Where each slave's port 0 is cabled (topology.hpp), per slave in the order given; empty: the
  // line, slave i's port 1 to slave i+1.
  Topology topology = {};
  // FoE firmware download with the ETG SSC's name/password checks and vdrive's image format on
  // every slave with FoE (ProductProfile::foe_strict_firmware_check; `vdrive run --foe-strict`).
  bool foe_strict_firmware_check = false;
};

class Network {
public:
  // Throws profile::ProfileError for an unknown product or a broken profile (esi::EsiError, one,
  // for a broken or ambiguous ESI file), std::invalid_argument for a topology the products' ports
  // cannot make (validate()) or a wire whose ends do not exist or differ in size. `clock` must
  // outlive the network (the ESCs read it).
  Network(std::span<const std::string> product_ids, const Clock& clock,
          const NetworkOptions& options = {});
  ~Network();
  Network(const Network&) = delete;
  Network& operator=(const Network&) = delete;

  // One Ethernet frame from the master, processed in place; `now` is its arrival time.
  // forward_frame() passes it through the ESCs only, as the silicon does while it is on the wire,
  // and says where it goes (back to the master, onward beyond this process, nowhere); the
  // firmware reacts afterwards in service_irqs(), so the event loop sends the frame first and a
  // slow firmware task (a flash write) never delays it. process_frame() does both and returns
  // true if the frame goes out (to the master, or onward), false if the line destroyed it.
  bool process_frame(std::span<std::uint8_t> ethernet_frame, Nanos now);
  FrameExit forward_frame(std::span<std::uint8_t> ethernet_frame, Nanos now) { return segment_.route(ethernet_frame, now); }
  // A frame forward_frame() sent onward came back at `now` (Segment::returned): true if it goes
  // on to the master.
  bool return_frame(std::span<std::uint8_t> ethernet_frame, Nanos now) { return segment_.returned(ethernet_frame, now); }
  // Runs the firmware of every slave whose PDI interrupt is asserted. `between` (optional) runs
  // after each slave's firmware call.
  void service_irqs(Nanos now, BetweenSlaves* between = nullptr);
  // Runs every ESC and firmware timer due at `now`, and firmware IRQs they raise. `between`
  // (optional) runs after each firmware call, not between the ESCs' own timers.
  void tick(Nanos now, BetweenSlaves* between = nullptr);
  // Earliest time tick() has work to do, or INT64_MAX.
  Nanos next_deadline() const;

  // Batched control steps, for serving in real time: every drive's steps may wait up to `wait`
  // (SlaveFirmware::set_control_step_batch) and run in a batch at the next interrupt or catch_up(),
  // so the loop wakes for the bus and not for each 125 us step. 0 (the default): each step is a
  // deadline of its own.
  void set_control_step_batch(Nanos wait);
  Nanos control_step_batch() const { return step_batch_; }
  // Runs every drive's control steps due by `now`, one step of each drive at a time, oldest first;
  // `between` (optional) runs after each step. With a batch, tick() and service_irqs() do this
  // first, so a frame overtakes a batch as finely as it does steps on time.
  void catch_up(Nanos now, BetweenSlaves* between = nullptr);
  // Switches every drive off and on again: ESC power-on reset (the EEPROM keeps its contents),
  // firmware restarts from Init with power-on values.
  void power_cycle(Nanos now);

  std::size_t size() const { return slaves_.size(); }
  const profile::ProductProfile& profile(std::size_t i) const { return slaves_[i]->profile; }
  esc::Esc& esc(std::size_t i) { return *slaves_[i]->esc; }
  firmware::SlaveFirmware& firmware(std::size_t i) { return *slaves_[i]->firmware; }
  Segment& segment() { return segment_; }

  // Signals (signal_point.hpp), on the loop's thread. resolve() throws std::invalid_argument for a
  // slave, entry or plant that does not exist, or an entry that is not an integer; write() throws
  // std::out_of_range for a value the point cannot hold. A value written to a wire's target is
  // replaced by the wire's at the next firmware call.
  SignalAccess resolve(const SignalPoint& point);
  SignalPoint parse_point(std::string_view text) const;  // names as NetworkOptions::slave_names
  // A named signal's point, else parse_point(); the message lists the names when it is neither.
  SignalPoint point_of(std::string_view name_or_point) const;
  std::string format_point(const SignalPoint& point) const;
  const std::vector<NamedSignal>& signals() const { return signals_; }
  const SignalAccess& signal(std::size_t i) const { return signal_access_[i]; }  // of signals()
  const std::vector<std::string>& slave_names() const { return slave_names_; }

private:
  struct Slave {
    profile::ProductProfile profile;  // the firmware keeps a reference to it
    std::unique_ptr<esc::Esc> esc;
    std::unique_ptr<firmware::SlaveFirmware> firmware;
  };

  // A wire resolved to what it copies (allocation-free on the frame path).
  struct Wire {
    SignalAccess from, to;
    bool same_entry_size = false;   // copy the bytes
  };
  void resolve_signals(const NetworkOptions& options);
  void copy_wires();

  std::vector<std::unique_ptr<Slave>> slaves_;  // stable addresses for the references above
  std::vector<Wire> wires_;
  std::vector<NamedSignal> signals_;
  std::vector<SignalAccess> signal_access_;
  std::vector<std::string> slave_names_;
  Segment segment_;
  Nanos step_batch_ = 0;
};

}  // namespace vdrive::network
