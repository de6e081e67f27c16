#include "vdrive/machine/eni_init_commands.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <optional>

#include "ethercat/al_state.hpp"
#include "ethercat/al_status_code.hpp"
#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"
#include "ethercat/sii.hpp"
#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/coe/sdo_server.hpp"
#include "vdrive/firmware/mailbox_sm_check.hpp"
#include "vdrive/firmware/pdo/pdo_limits.hpp"
#include "vdrive/firmware/pdo/pdo_write_rules.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::machine {
namespace {

namespace sdo = ecat::coe::sdo;
using ecat::AlState;

// The transitions are tried here, not judged: every check passes.
class TakeEveryTransition final : public firmware::TransitionHooks {
public:
  firmware::CheckResult check_init_to_preop() override { return firmware::CheckResult::pass(); }
  firmware::CheckResult check_init_to_boot() override { return firmware::CheckResult::pass(); }
  firmware::CheckResult check_preop_to_safeop() override { return firmware::CheckResult::pass(); }
  firmware::CheckResult check_safeop_to_op() override { return firmware::CheckResult::pass(); }
  void entered(AlState, AlState) override {}
};

// The state the master sends a CoE command of `transition` in: the lower of the two states, and
// never Init (no mailbox there). nullopt for transitions without a mailbox (Init, Bootstrap).
std::optional<AlState> state_of(const std::string& transition) {
  if (transition == "IP" || transition == "PS" || transition == "SP" || transition == "OP") return AlState::PreOp;
  if (transition == "SO" || transition == "OS") return AlState::SafeOp;
  return std::nullopt;
}

// The device's SDO server on a fresh copy of its dictionary, with its PDO write rules.
class Device {
public:
  Device(const profile::ProductProfile& profile, const od::Dictionary& dictionary)
      : store_(dictionary), esm_(firmware::EsmTraits::of(profile)), server_(profile, store_, esm_, nullptr) {
    esm_.reset();
    firmware::pdo::install_pdo_write_rules(store_, esm_, firmware::pdo::limits_for(profile));
  }

  void enter(AlState target) {
    // Init -> PreOp -> SafeOp upwards, one step at a time as a master goes; straight down.
    while (esm_.state() != target) {
      const AlState next = esm_.state() == AlState::Init ? AlState::PreOp
                           : (esm_.state() == AlState::PreOp && target == AlState::SafeOp) ? AlState::SafeOp
                                                                                           : target;
      esm_.on_al_control(ecat::AlControl{static_cast<std::uint8_t>(next)}, 0, hooks_);
      if (esm_.state() != next) return;  // cannot happen with every check passing; do not loop
    }
  }

  // The abort the device answers the command with (Ok: none).
  od::SdoAbort run(const esi::EniCoeCommand& c) {
    std::vector<std::uint8_t> request(sdo::kNormalData + (c.ccs == 1 ? c.data.size() : 0), 0);
    ecat::coe::put_coe_header(request, ecat::coe::Service::SdoRequest);
    ecat::put_le16(request, sdo::kIndex, c.index);
    request[sdo::kSubindex] = c.subindex;
    const std::uint8_t ca = c.complete_access ? sdo::kCompleteAccess : 0;
    if (c.ccs != 1) {
      request[sdo::kCommand] = static_cast<std::uint8_t>(2 << sdo::kCommandSpecifierShift | ca);
    } else if (c.data.size() <= 4 && !c.complete_access) {
      // Expedited, as masters send up to four bytes.
      request.resize(sdo::kInitiateSize);
      request[sdo::kCommand] = static_cast<std::uint8_t>(1 << sdo::kCommandSpecifierShift | sdo::kExpedited |
                                                         sdo::kSizeIndicator | ((4 - c.data.size()) << 2));
      std::copy(c.data.begin(), c.data.end(), request.begin() + sdo::kData);
    } else {
      request[sdo::kCommand] = static_cast<std::uint8_t>(1 << sdo::kCommandSpecifierShift | sdo::kSizeIndicator | ca);
      ecat::put_le32(request, sdo::kData, static_cast<std::uint32_t>(c.data.size()));
      std::copy(c.data.begin(), c.data.end(), request.begin() + sdo::kNormalData);
    }
    const std::size_t n = server_.on_request(request, reply_).length;
    server_.reset();  // an upload in segments is not followed further: its start is the answer
    if (n >= sdo::kInitiateSize && (reply_[sdo::kCommand] & 0xE0) == sdo::kAbort)
      return static_cast<od::SdoAbort>(ecat::get_le32(reply_, sdo::kData));
    return od::SdoAbort::Ok;
  }

private:
  od::ObjectStore store_;
  firmware::AlStateMachine esm_;
  firmware::coe::SdoServer server_;
  TakeEveryTransition hooks_;
  std::vector<std::uint8_t> reply_ = std::vector<std::uint8_t>(0x10000);
};

std::string transitions_text(const std::vector<std::string>& t) {
  std::string s;
  for (const std::string& x : t) s += (s.empty() ? "" : ",") + x;
  return s;
}

void check_coe(const esi::EniSlave& slave, const profile::ProductProfile& profile, const od::Dictionary& dictionary,
               const std::string& who, std::vector<std::string>& notes) {
  if (slave.coe_init_commands.empty()) return;
  if ((profile.mailbox.protocols & ecat::sii::mailbox_protocol::kCoE) == 0) {
    notes.push_back(fmt::format("{}: {} CoE init commands, but the device has no CoE: the master gets no answer to "
                                "them", who, slave.coe_init_commands.size()));
    return;
  }
  Device device(profile, dictionary);
  auto run = [&](const esi::EniCoeCommand& c, AlState state) {
    device.enter(state);
    const od::SdoAbort abort = device.run(c);
    if (abort == od::SdoAbort::Ok) return;
    notes.push_back(fmt::format("{}: CoE init command (line {}, {}{}): {} {:04X}h:{:02X}h{}: the device answers abort "
                                "{:08X}h ({})", who, c.line, transitions_text(c.transitions),
                                c.comment.empty() ? "" : ", " + c.comment, c.ccs == 1 ? "download" : "upload", c.index,
                                c.subindex, c.complete_access ? " (complete access)" : "",
                                static_cast<std::uint32_t>(abort), od::describe(abort)));
  };
  // Start-up order: the upward transitions, each with its commands as written; then the rest.
  std::vector<bool> done(slave.coe_init_commands.size(), false);
  for (const char* t : {"IP", "PS", "SO"}) {
    for (std::size_t i = 0; i < slave.coe_init_commands.size(); ++i) {
      const esi::EniCoeCommand& c = slave.coe_init_commands[i];
      if (c.disabled || std::find(c.transitions.begin(), c.transitions.end(), t) == c.transitions.end()) continue;
      run(c, *state_of(t));
      done[i] = true;
    }
  }
  for (std::size_t i = 0; i < slave.coe_init_commands.size(); ++i) {
    const esi::EniCoeCommand& c = slave.coe_init_commands[i];
    if (done[i] || c.disabled) continue;
    for (const std::string& t : c.transitions)
      if (const std::optional<AlState> s = state_of(t)) {
        run(c, *s);
        break;
      }
  }
}

void check_registers(const esi::EniSlave& slave, const profile::ProductProfile& profile, const std::string& who,
                     std::vector<std::string>& notes) {
  const std::optional<esi::EniSmWrite> sm0 = slave.sm_written(0), sm1 = slave.sm_written(1);
  if (profile.has_mailbox() && sm0 && sm1) {
    std::array<firmware::SmChannel, 2> sms{};
    for (std::size_t n = 0; n < 2; ++n) {
      const esi::EniSmWrite& w = n == 0 ? *sm0 : *sm1;
      sms[n].start = w.start;
      sms[n].length = w.length;
      sms[n].control = w.control;
      sms[n].activate = w.enable ? 1 : 0;
    }
    const firmware::MailboxSmFault fault = firmware::check_mailbox_sms(sms, profile.mailbox_rules);
    if (fault != firmware::MailboxSmFault::Ok) {
      const std::uint16_t code = profile.al_codes.invalid_mailbox_config;
      notes.push_back(fmt::format("{}: register init commands (lines {}, {}) set the mailbox SyncManagers up as "
                                  "SM0 {:04X}h/{} bytes/{:02X}h, SM1 {:04X}h/{} bytes/{:02X}h: the device refuses "
                                  "Pre-Op with AL status code {:04X}h ({}): {}", who, sm0->line, sm1->line, sm0->start,
                                  sm0->length, sm0->control, sm1->start, sm1->length, sm1->control, code,
                                  ecat::al_status_code::name(code), firmware::describe(fault)));
    }
  }
  if (const std::optional<std::uint16_t> a = slave.dc_activation()) {
    const auto activation = static_cast<std::uint8_t>(*a >> 8);
    const std::vector<std::uint8_t>& ok = profile.sync.accepted_dc_activation;
    if (std::find(ok.begin(), ok.end(), activation) == ok.end()) {
      const std::uint16_t code = profile.al_codes.invalid_dc_sync_config;
      notes.push_back(fmt::format("{}: a register init command activates DC with 0981h = {:02X}h: the device refuses "
                                  "Safe-Op with AL status code {:04X}h ({})", who, activation, code,
                                  ecat::al_status_code::name(code)));
    }
  }
}

}  // namespace

std::vector<std::string> check_init_commands(const esi::EniSlave& slave, const profile::ProductProfile& profile,
                                             const od::Dictionary& dictionary, const std::string& who) {
  std::vector<std::string> notes;
  check_coe(slave, profile, dictionary, who, notes);
  check_registers(slave, profile, who, notes);
  return notes;
}

}  // namespace vdrive::machine
