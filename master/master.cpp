#include "master/master.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <string_view>

#include "master/registers.hpp"
#include "master/sii.hpp"

namespace vdrive::master {

Master::Master(link::Link& link, MasterOptions options)
    : own_clock_(std::make_unique<MonotonicClock>()), clock_(*own_clock_), options_(options),
      transport_(link, clock_, options.transport) {}

Master::Master(link::Link& link, const Clock& clock, MasterOptions options)
    : clock_(clock), options_(options), transport_(link, clock_, options.transport) {}

Master::~Master() = default;

namespace {
bool is(const Wkc& wkc, std::uint16_t expected) { return wkc && *wkc == expected; }

// Checks a working counter; the message is only built on failure (state polling calls this in a
// loop and should not allocate).
constexpr std::size_t kLine = SIZE_MAX;  // "the whole line", not one slave
void require(const Wkc& wkc, std::uint16_t expected, std::string_view what, std::size_t slave = kLine) {
  if (wkc && *wkc == expected) return;
  const std::string who = slave == kLine ? std::string(what) : fmt::format("slave {}: {}", slave + 1, what);  // from 1, as people count
  if (!wkc) throw MasterError(fmt::format("{}: no reply from the line", who));
  throw MasterError(fmt::format("{}: working counter {} (expected {})", who, *wkc, expected));
}
}  // namespace

bool Master::line_to_init() {
  const auto n = static_cast<std::uint16_t>(slaves_.size());
  require(transport_.bwr_value<std::uint8_t>(reg::kAlControl, static_cast<std::uint8_t>(AlState::Init) | reg::kAlAcknowledge),
          n, "BWR AL control (Init + ack)");
  // A BRD ORs every slave's AL status into one word: no state bit beyond Init's (1) means no
  // slave is anywhere else (Pre-Op 2, Safe-Op 4, Op 8, Boot 3).
  constexpr auto kAboveInit = static_cast<std::uint8_t>(reg::kAlStateMask & ~static_cast<unsigned>(AlState::Init));
  const Nanos deadline = clock_.now() + options_.state_timeout;
  for (;;) {
    std::array<std::uint8_t, 2> status{};
    require(transport_.brd(reg::kAlStatus, status), n, "BRD AL status");
    if ((status[0] & kAboveInit) == 0) return true;
    if (clock_.now() >= deadline) return false;
    sleep_poll();
  }
}

void Master::reset_line() {
  // The same reset a master such as SOEM applies before configuring: every slave back to a
  // known, unconfigured state, whatever a previous master left behind.
  const auto n = static_cast<std::uint16_t>(slaves_.size());
  std::array<std::uint8_t, 64> zeros{};
  // Init first, and only then the registers. A slave still in Pre-Op or higher (where the last
  // command left it) checks its mailbox SyncManagers whenever they change: clearing them under
  // it is a wrong mailbox configuration, AL 0016h, which the A6B raises as Err81.1 (detected in
  // PreOP, SafeOP and OP, L33400-L33446) and the DS5C1 as E-811 (L7125), both 603Fh FF51h,
  // still there after the AL acknowledge until a fault reset. SOEM's ecx_detect_slaves likewise
  // requests Init before it touches anything. A slave that takes longer than the state timeout
  // (a drive finishing an Err88.2 stop in Op, A6B L3365-L3371) is reset anyway, as before.
  line_to_init();
  require(transport_.bwr_value<std::uint8_t>(reg::kDlControlLoop, 0x00), n, "BWR DL control (loops auto)");
  require(transport_.bwr_value<std::uint16_t>(reg::kEcatEventMask, 0x0004), n, "BWR ECAT event mask");
  require(transport_.bwr(reg::kRxErrorCounters, std::span(zeros.data(), 8)), n, "BWR RX error counters");
  require(transport_.bwr(reg::kFmmu0, std::span(zeros.data(), 3 * reg::kFmmuSize)), n, "BWR FMMU 0-2");
  require(transport_.bwr(reg::kSm0, std::span(zeros.data(), 4 * reg::kSmSize)), n, "BWR SM 0-3");
  require(transport_.bwr_value<std::uint8_t>(reg::kDcSyncActivation, 0), n, "BWR DC sync activation");
  require(transport_.bwr(reg::kDcSystemTime, std::span(zeros.data(), 4)), n, "BWR DC system time");
  require(transport_.bwr_value<std::uint16_t>(reg::kDcSpeedCounterStart, 0x1000), n, "BWR DC speed counter");
  require(transport_.bwr_value<std::uint16_t>(reg::kDcTimeFilter, 0x0C00), n, "BWR DC time filter");
  require(transport_.bwr_value<std::uint8_t>(reg::kDlControlAlias, 0x00), n, "BWR DL control (alias off)");
  require(transport_.bwr_value<std::uint8_t>(reg::kAlControl, static_cast<std::uint8_t>(AlState::Init) | reg::kAlAcknowledge),
          n, "BWR AL control (Init + ack)");
  require(transport_.bwr_value<std::uint8_t>(reg::kEepromConfig, reg::kEepromForceEcat), n, "BWR EEPROM force ECAT");
  require(transport_.bwr_value<std::uint8_t>(reg::kEepromConfig, 0x00), n, "BWR EEPROM to ECAT");
}

std::size_t Master::scan() {
  slaves_.clear();
  sdos_.clear();
  mailboxes_.clear();
  std::array<std::uint8_t, 2> type{};
  const Wkc count = transport_.brd(reg::kType, type);
  if (!count) throw MasterError("no reply to BRD 0x0000: is the interface up and a slave connected?");
  slaves_.resize(*count);
  if (slaves_.empty()) return 0;
  reset_line();

  for (std::size_t i = 0; i < slaves_.size(); ++i) {
    Slave& s = slaves_[i];
    s.position = static_cast<std::uint16_t>(i);
    s.station = static_cast<std::uint16_t>(kFirstStationAddress + i);
    require(transport_.apwr_value<std::uint16_t>(s.position, reg::kStationAddress, s.station), 1,
            "APWR station address", i);
    const auto back = transport_.fprd_value<std::uint16_t>(s.station, reg::kStationAddress);
    if (!back || *back != s.station) {
      throw MasterError(fmt::format("slave {}: station address 0x{:04X} does not read back", i + 1, s.station));
    }
    std::array<std::uint8_t, 10> esc{};
    require(transport_.fprd(s.station, reg::kType, esc), 1, "FPRD ESC information", i);
    s.esc_type = esc[0];
    s.esc_revision = esc[1];
    s.esc_build = static_cast<std::uint16_t>(esc[2] | (esc[3] << 8));
    s.fmmu_count = esc[4];
    s.sm_count = esc[5];
    s.dl_status = transport_.fprd_value<std::uint16_t>(s.station, reg::kDlStatus).value_or(0);
    const auto features = transport_.fprd_value<std::uint16_t>(s.station, reg::kFeatures).value_or(0);
    s.dc_supported = (features & reg::kFeatureDc) != 0;
  }

  for (Slave& s : slaves_) {
    try {
      SiiReader sii(transport_, s.station, options_.sii_busy_timeout);
      sii.take_to_ecat();
      s.info = parse_sii(sii.read_image());
    } catch (const SiiError& e) {
      throw MasterError(fmt::format("slave {}: SII: {}", s.position + 1, e.what()));
    }
    s.mailbox_sm[0] = SmSetting{s.info.mailbox_rx_offset, s.info.mailbox_rx_size, reg::kSmControlMailboxWrite,
                                s.info.mailbox_rx_size ? reg::kSmActivateEnable : std::uint8_t{0}};
    s.mailbox_sm[1] = SmSetting{s.info.mailbox_tx_offset, s.info.mailbox_tx_size, reg::kSmControlMailboxRead,
                                s.info.mailbox_tx_size ? reg::kSmActivateEnable : std::uint8_t{0}};
    read_al_status(s.position);
  }
  mailboxes_.resize(slaves_.size());
  sdos_.resize(slaves_.size());
  return slaves_.size();
}

SdoClient& Master::sdo(std::size_t index) {
  Slave& s = slaves_.at(index);
  if (!sdos_[index]) {
    const MailboxConfig config{s.station, s.mailbox_sm[0].start, s.mailbox_sm[0].length, s.mailbox_sm[1].start,
                               s.mailbox_sm[1].length};
    mailboxes_[index] = std::make_unique<MailboxClient>(transport_, config, mailbox_timeout_, &s.mailbox_counter);
    mailboxes_[index]->flush();  // a reply left over from an earlier master is not ours
    sdos_[index] = std::make_unique<SdoClient>(*mailboxes_[index]);
  }
  return *sdos_[index];
}

AlStatus Master::read_al_status(std::size_t index) {
  Slave& s = slaves_.at(index);
  std::array<std::uint8_t, 6> al{};  // 0x0130 status, 0x0132 reserved, 0x0134 status code
  require(transport_.fprd(s.station, reg::kAlStatus, al), 1, "FPRD AL status", index);
  const auto status = static_cast<std::uint16_t>(al[0] | (al[1] << 8));
  s.al.state = static_cast<std::uint8_t>(status & reg::kAlStateMask);
  s.al.error = (status & reg::kAlErrorFlag) != 0;
  s.al.status_code = s.al.error ? static_cast<std::uint16_t>(al[4] | (al[5] << 8)) : 0;
  return s.al;
}

bool Master::acknowledge_error(std::size_t index) {
  Slave& s = slaves_.at(index);
  if (s.al.error && s.al.status_code != 0) s.refused_code = s.al.status_code;
  const auto value = static_cast<std::uint16_t>(s.al.state | reg::kAlAcknowledge);
  return is(transport_.fpwr_value<std::uint16_t>(s.station, reg::kAlControl, value), 1);
}

void Master::configure_mailbox(Slave& s, bool boot) {
  if (s.position < mailboxes_.size() && mailboxes_[s.position]) mailboxes_[s.position]->restarted();
  // Bootstrap uses the SII's boot mailbox (words 0x14-0x17) with the same control bytes.
  const std::array<SmSetting, 2> boot_sm{
      SmSetting{s.info.boot_rx_offset, s.info.boot_rx_size, reg::kSmControlMailboxWrite, reg::kSmActivateEnable},
      SmSetting{s.info.boot_tx_offset, s.info.boot_tx_size, reg::kSmControlMailboxRead, reg::kSmActivateEnable}};
  for (std::size_t n = 0; n < s.mailbox_sm.size(); ++n) {
    const SmSetting& sm = boot ? boot_sm[n] : s.mailbox_sm[n];
    const std::array<std::uint8_t, 8> regs{static_cast<std::uint8_t>(sm.start), static_cast<std::uint8_t>(sm.start >> 8),
                                           static_cast<std::uint8_t>(sm.length), static_cast<std::uint8_t>(sm.length >> 8),
                                           sm.control, 0x00, sm.activate, 0x00};
    const auto base = static_cast<std::uint16_t>(reg::kSm0 + n * reg::kSmSize);
    // An ESC ignores writes to start/length/control while the SM is enabled: disable it first
    // (it may still hold an earlier, refused configuration).
    require(transport_.fpwr_value<std::uint8_t>(s.station, static_cast<std::uint16_t>(base + reg::kSmActivateOffset), 0),
            1, n == 0 ? "FPWR SM0 disable" : "FPWR SM1 disable", s.position);
    require(transport_.fpwr(s.station, base, regs), 1, n == 0 ? "FPWR SM0" : "FPWR SM1", s.position);
  }
}

void Master::sleep_poll() {
  // Only a real clock needs the pause; under a virtual clock the link moves time. The pause is
  // the link's own wait, so a link that serves the line on this thread (the scenario runner's
  // real-time wire) keeps it running.
  if (dynamic_cast<const VirtualClock*>(&clock_) == nullptr) transport_.idle_until(clock_.now() + options_.poll_interval);
}

bool Master::step_to(Slave& s, AlState target) {
  const auto from = static_cast<AlState>(s.al.state);
  if ((target == AlState::PreOp || target == AlState::Boot) && from == AlState::Init && s.info.has_mailbox()) {
    configure_mailbox(s, target == AlState::Boot);
  }
  require(transport_.fpwr_value<std::uint16_t>(s.station, reg::kAlControl, static_cast<std::uint16_t>(target)), 1,
          "FPWR AL control", s.position);
  const Nanos deadline = clock_.now() + options_.state_timeout;
  for (;;) {
    const AlStatus al = read_al_status(s.position);
    if (al.error) {
      acknowledge_error(s.position);
      return false;
    }
    if (al.state == static_cast<std::uint8_t>(target)) return true;
    if (clock_.now() >= deadline) return false;
    sleep_poll();
  }
}

bool Master::request_state(std::size_t index, AlState target) {
  Slave& s = slaves_.at(index);
  read_al_status(index);
  if (s.al.error) {
    acknowledge_error(index);
    read_al_status(index);
  }
  // The path through the state machine: Init <-> Pre-Op <-> Safe-Op <-> Op, Init <-> Boot.
  // Going down may skip states (the ESM allows Op -> Init directly); going up may not.
  auto rank = [](AlState st) {
    switch (st) {
      case AlState::Init: return 1;
      case AlState::PreOp: return 2;
      case AlState::SafeOp: return 3;
      case AlState::Op: return 4;
      case AlState::Boot: return 0;
    }
    return -1;
  };
  for (int guard = 0; guard < 8; ++guard) {
    const auto current = static_cast<AlState>(s.al.state);
    if (current == target) return true;
    AlState next = target;
    if (target == AlState::Boot || current == AlState::Boot) {
      next = current == AlState::Boot ? AlState::Init : (current == AlState::Init ? AlState::Boot : AlState::Init);
    } else if (rank(target) > rank(current) && rank(current) >= 1) {
      next = static_cast<AlState>(rank(current) == 1 ? AlState::PreOp : rank(current) == 2 ? AlState::SafeOp : AlState::Op);
    } else if (rank(current) < 1) {
      next = AlState::Init;  // an unknown state: start over from Init
    }
    if (!step_to(s, next)) return false;
  }
  return s.state() == target;
}

bool Master::request_state(AlState target) {
  bool all = true;
  for (std::size_t i = 0; i < slaves_.size(); ++i) all = request_state(i, target) && all;
  return all;
}

std::string describe(const Slave& s) {
  std::string text = fmt::format("{}  0x{:04X}  vendor=0x{:08X}  product=0x{:08X}  revision=0x{:08X}  {:<20}  {}",
                                 s.position + 1, s.station, s.info.vendor_id, s.info.product_code, s.info.revision,
                                 s.info.name.empty() ? "(no name)" : s.info.name, to_string(s.state()));
  if (s.al.error) {
    text += fmt::format("  error 0x{:04X} ({})", s.al.status_code, al_status_code_text(s.al.status_code));
  } else if (s.refused_code != 0) {
    text += fmt::format("  last refused with 0x{:04X} ({})", s.refused_code, al_status_code_text(s.refused_code));
  }
  return text;
}

std::string label(const Slave& s) { return ecat::slave_label(s.position, s.station, s.info.name); }

std::size_t find_slave(const Master& master, const ecat::SlaveRef& ref) {
  std::vector<std::uint16_t> stations;
  for (const Slave& s : master.slaves()) stations.push_back(s.station);
  return ecat::slave_index(ref, stations);
}

}  // namespace vdrive::master
