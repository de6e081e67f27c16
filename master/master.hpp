#pragma once
// ecmaster: a small EtherCAT master over a vdrive::link::Link, used by the tests, the demo and
// the `vdrive-master` tool. It brings a line up the way SOEM's ec_config_init does:
//
//   Master m(link);
//   m.scan();                           // count, reset, address 0x1001.., read SII of every slave
//   m.slaves()[0].info.name;            // identity, mailbox, SMs, PDOs from the SII
//   m.request_state(AlState::PreOp);    // configures mailbox SM0/SM1 from the SII first
//   m.sdo(0).upload_value<std::uint32_t>(0x1018, 1);   // CoE (coe.hpp)
//
// Process data, DC and the cyclic task are free functions over a Master: process_data.hpp,
// dc.hpp, cyclic_task.hpp; op_run.hpp chains them all the way to Op (docs/master.md).
//
// Errors on the wire (no reply after retries) throw MasterError; a slave that refuses a state is
// not an exception: request_state() returns false and the slave carries its AL status code.
#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "ethercat/slave_ref.hpp"
#include "master/al_state.hpp"
#include "master/coe.hpp"
#include "master/mailbox.hpp"
#include "master/process_data.hpp"
#include "master/slave_info.hpp"
#include "master/transport.hpp"
#include "vdrive/link/link.hpp"

namespace vdrive::master {

class MasterError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

constexpr std::uint16_t kFirstStationAddress = 0x1001;

// One SyncManager's register block (0x0800 + 8*n) as the master writes it.
struct SmSetting {
  std::uint16_t start = 0;
  std::uint16_t length = 0;
  std::uint8_t control = 0;
  std::uint8_t activate = 0;     // bit 0: enable
};

struct Slave {
  std::uint16_t position = 0;          // 0-based place in the line
  std::uint16_t station = 0;           // configured station address (0x1001 + position)
  std::uint8_t esc_type = 0, esc_revision = 0;
  std::uint16_t esc_build = 0;
  std::uint8_t fmmu_count = 0, sm_count = 0;
  std::uint16_t dl_status = 0;
  SlaveInfo info;                      // from the SII
  // SM0/SM1 written before Pre-Op (and Boot). Derived from the SII at scan(); callers may change
  // them before request_state() (e.g. to test a slave's mailbox checks).
  std::array<SmSetting, 2> mailbox_sm{};
  AlStatus al;                         // last AL status read
  // The AL status code of the last error the master acknowledged (why a state was refused), kept
  // because acknowledging clears it on the slave; 0 = none since scan().
  std::uint16_t refused_code = 0;
  std::uint8_t mailbox_counter = 0;    // last mailbox counter sent (1..7), shared by its clients
  SlaveProcessData process_data;       // filled by configure_process_data()
  bool dc_supported = false;           // ESC feature 0x0008 bit 2, read at scan()
  std::int64_t dc_delay = 0;           // propagation delay from the reference clock (ns), by configure_dc()
  // Where the slave hangs, as configure_dc() reconstructs it from the receive times (dc_topology.hpp):
  // the parent's position and port; the first slave is its own parent, port 0.
  std::uint16_t parent = 0;
  int parent_port = 0;
  std::int64_t dc_offset = 0;          // system time offset written to 0x0920
  AlState state() const { return static_cast<AlState>(al.state); }
};

struct MasterOptions {
  TransportOptions transport;
  Nanos state_timeout = 5'000'000'000;      // per state request (ETG: Init->PreOp up to 5 s)
  Nanos sii_busy_timeout = 100'000'000;
  Nanos poll_interval = 1'000'000;          // between AL status polls (only with a real clock)
};

class Master {
public:
  // Real time (MonotonicClock owned by the master).
  explicit Master(link::Link& link, MasterOptions options = {});
  // Given clock: VirtualClock in tests, where the link advances time.
  Master(link::Link& link, const Clock& clock, MasterOptions options = {});
  ~Master();
  Master(const Master&) = delete;
  Master& operator=(const Master&) = delete;

  // Counts the slaves (BRD 0x0000), takes them to Init and waits for it, resets them to a known
  // state (FMMUs/SMs cleared, loops auto, alias off, EEPROM to ECAT), assigns station addresses
  // 0x1001.. (APWR 0x0010) and checks them back (FPRD), then reads every SII. Returns the number
  // of slaves. Throws MasterError.
  std::size_t scan();

  std::vector<Slave>& slaves() { return slaves_; }
  const std::vector<Slave>& slaves() const { return slaves_; }

  // Takes every slave to `target` (through the states in between, as ETG.1000.6 requires).
  // Returns true when all reached it; each slave's `al` says where it stands.
  bool request_state(AlState target);
  // One slave. Before Pre-Op/Boot from Init, writes SM0/SM1 from `mailbox_sm`.
  bool request_state(std::size_t slave, AlState target);
  // Reads AL status (and AL status code) into slaves()[slave].al and returns it.
  AlStatus read_al_status(std::size_t slave);
  // Acknowledges an error indication: AL control = current state | 0x10.
  bool acknowledge_error(std::size_t slave);

  // The CoE client of a slave; its mailbox must be running (Pre-Op or higher). Created on first
  // use with SM0/SM1 as configured (mailbox_sm). Throws MailboxError for a slave without mailbox.
  SdoClient& sdo(std::size_t slave);
  // Mailbox reply timeout for clients created from now on.
  void set_mailbox_timeout(Nanos timeout) { mailbox_timeout_ = timeout; }

  Transport& transport() { return transport_; }
  const Clock& clock() const { return clock_; }

private:
  bool step_to(Slave& slave, AlState target);
  void configure_mailbox(Slave& slave, bool boot);
  void reset_line();
  // AL control Init + acknowledge to every slave, then waits (up to the state timeout) until
  // none is in another state; false if one still is.
  bool line_to_init();
  void sleep_poll();

  std::unique_ptr<Clock> own_clock_;
  const Clock& clock_;
  MasterOptions options_;
  Transport transport_;
  std::vector<Slave> slaves_;
  Nanos mailbox_timeout_ = 1'000'000'000;
  std::vector<std::unique_ptr<MailboxClient>> mailboxes_;
  std::vector<std::unique_ptr<SdoClient>> sdos_;
};

// One line for people: position (from 1), station address, identity, name, AL state and, after a
// refused state change, the AL status code with its meaning.
std::string describe(const Slave& slave);

// "slave 2 @0x1002 NAME" (ethercat/slave_ref.hpp): how every vdrive-master message names a slave.
std::string label(const Slave& slave);

// The index into master.slaves() of the slave `ref` names (position from 1, or station address);
// std::invalid_argument says which slaves there are.
std::size_t find_slave(const Master& master, const ecat::SlaveRef& ref);

}  // namespace vdrive::master
