#include "vdrive/fault/fault_injector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "esc_model/esc_faults.hpp"
#include "ethercat/slave_ref.hpp"
#include "plant/axis_faults.hpp"
#include "plant/plant.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/network/slave_lookup.hpp"
#include "vdrive/drive/injected_fault.hpp"
#include "vdrive/fault/wire_impairment.hpp"
#include "vdrive/firmware/mailbox/mailbox_faults.hpp"
#include "vdrive/firmware/mailbox/mailbox_module.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::fault {
namespace {

constexpr Nanos kNever = std::numeric_limits<Nanos>::max();

std::optional<drive::InjectedFault> drive_cause(FaultKind kind) {
  switch (kind) {
    case FaultKind::encoder_error: return drive::InjectedFault::encoder_error;
    case FaultKind::overload: return drive::InjectedFault::overload;
    case FaultKind::over_voltage: return drive::InjectedFault::over_voltage;
    case FaultKind::under_voltage: return drive::InjectedFault::under_voltage;
    case FaultKind::main_power_off: return drive::InjectedFault::main_power_off;
    case FaultKind::over_temperature: return drive::InjectedFault::over_temperature;
    case FaultKind::following_error: return drive::InjectedFault::following_error;
    default: return std::nullopt;
  }
}

bool towards(WireDirection want, Direction d) {
  return want == WireDirection::both || (want == WireDirection::to_slaves) == (d == Direction::to_slaves);
}

}  // namespace

FaultInjector::FaultInjector(network::Network& network, WireImpairment* wire) : network_(network), wire_(wire) {}

void FaultInjector::check(const FaultSpec& s) const {
  const FaultKindInfo& i = info(s.kind);
  const auto where = [&] { return describe(s); };
  const int n = static_cast<int>(network_.size());
  if (s.kind == FaultKind::link_down) {
    if (s.slave > n) refuse_slave(s, s.slave);
    if (s.slave < 1) throw FaultError(fmt::format("{}: the network has cables into slaves 1..{}", where(), n));
    if (network_.segment().cabled_at(static_cast<std::size_t>(s.slave - 1), s.port) < 0)
      throw FaultError(fmt::format("{}: nothing is cabled to port {} of slave {}", where(), s.port, s.slave));
    return;
  }
  if (i.layer == Layer::wire) {
    if (!wire_) throw FaultError(fmt::format("{}: this link has no wire fault stage", where()));
    if (s.probability < 0.0 || s.probability > 1.0)
      throw FaultError(fmt::format("{}: probability must be between 0 and 1", where()));
    if (s.delay < 0) throw FaultError(fmt::format("{}: delay must not be negative", where()));
    return;
  }
  if (s.slave > n) refuse_slave(s, s.slave);
  if (s.slave < 1) throw FaultError(fmt::format("{}: no slave {} (the line has {})", where(), s.slave, n));
  auto& fw = network_.firmware(static_cast<std::size_t>(s.slave - 1));
  if ((i.layer == Layer::drive && !fw.drive()) || (i.layer == Layer::plant && !fw.plant()))
    throw FaultError(fmt::format("{}: slave {} ({}) has no drive", where(), s.slave,
                                 network_.profile(static_cast<std::size_t>(s.slave - 1)).id));
  if (s.kind == FaultKind::lost_reply || s.kind == FaultKind::duplicate_reply) {
    if (s.count < 1) throw FaultError(fmt::format("{}: count must be at least 1", where()));
  }
  if (s.kind == FaultKind::load_change && !(s.load_scale > 0.0))
    throw FaultError(fmt::format("{}: load_scale must be > 0", where()));
  if (s.kind == FaultKind::load_change && !(s.friction_scale >= 0.0 && std::isfinite(s.friction_scale)))
    throw FaultError(fmt::format("{}: friction_scale must be >= 0", where()));
}

void FaultInjector::refuse_slave(const FaultSpec& s, int slave) const {
  const std::size_t n = network_.size();
  if (static_cast<std::size_t>(slave) <= n + later_slaves_)
    throw FaultError(fmt::format("{}: slave {} is served by another process of this run (--processes); faults reach "
                                 "this process's slaves, 1 to {} (vdrive fault reaches every part through the run's "
                                 "control socket)",
                                 describe(s), slave, n));
  if (s.kind == FaultKind::link_down)
    throw FaultError(fmt::format("{}: the network has cables into slaves 1..{}", describe(s), n + later_slaves_));
  throw FaultError(fmt::format("{}: no slave {} (the line has {})", describe(s), slave, n + later_slaves_));
}

FaultSpec FaultInjector::with_position(const FaultSpec& s) const {
  if (s.station == 0 || s.slave != 0) return s;
  FaultSpec found = s;
  try {
    found.slave = static_cast<int>(network::find_slave(network_, {ecat::SlaveRef::Kind::address, s.station})) + 1;
  } catch (const std::invalid_argument& e) {
    throw FaultError(fmt::format("{}: {}{}", describe(s), e.what(),
                                 later_slaves_ != 0 ? fmt::format("; slaves after {} are served by other processes of this run, "
                                                                  "whose addresses are not known here",
                                                                  network_.size())
                                                    : std::string()));
  }
  return found;
}

int FaultInjector::inject(const FaultSpec& requested, Nanos now) {
  const FaultSpec spec = with_position(requested);
  check(spec);
  if (info(spec.kind).one_shot) {
    apply_one_shot(spec, now);
    return next_id_++;
  }
  ActiveFault f{next_id_++, spec, now, spec.duration > 0 ? now + spec.duration : kNever};
  active_.push_back(f);
  apply_layer(spec, true, now);
  return f.id;
}

void FaultInjector::apply_one_shot(const FaultSpec& s, Nanos now) {
  auto& fw = network_.firmware(static_cast<std::size_t>(s.slave - 1));
  if (s.kind == FaultKind::alarm) {
    if (!fw.drive()->raise_alarm(s.alarm, now))
      throw FaultError(fmt::format("{}: {} has no alarm \"{}\" in its alarm table", describe(s),
                                   network_.profile(static_cast<std::size_t>(s.slave - 1)).id, s.alarm));
    return;
  }
  firmware::mailbox::MailboxFaults m = fw.mailbox().faults();
  switch (s.kind) {
    case FaultKind::lost_reply: m.lose_replies += s.count; break;
    case FaultKind::duplicate_reply: m.duplicate_replies += s.count; break;
    case FaultKind::toggle_error: m.toggle_error = true; break;
    case FaultKind::sdo_abort: m.abort_code = s.abort_code; break;
    default: break;
  }
  fw.mailbox().set_faults(m);
}

void FaultInjector::set_drive_cause(const FaultSpec& s, bool active, Nanos now) {
  const auto cause = drive_cause(s.kind);
  if (!cause) return;
  // Another active fault of the same cause on the same slave keeps it present.
  if (!active) {
    for (const ActiveFault& f : active_)
      if (f.spec.kind == s.kind && f.spec.slave == s.slave) return;
  }
  network_.firmware(static_cast<std::size_t>(s.slave - 1)).drive()->set_injected_fault(*cause, active, now);
}

void FaultInjector::apply_wire() {
  if (!wire_) return;
  for (const Direction d : {Direction::to_slaves, Direction::to_master}) {
    WireSettings w;
    double keep = 1.0, clean = 1.0, single = 1.0, in_order = 1.0;
    for (const ActiveFault& f : active_) {
      const FaultSpec& s = f.spec;
      if (info(s.kind).layer != Layer::wire || !towards(s.direction, d)) continue;
      switch (s.kind) {
        case FaultKind::drop: keep *= 1.0 - s.probability; break;
        case FaultKind::corrupt: clean *= 1.0 - s.probability; break;
        case FaultKind::duplicate: single *= 1.0 - s.probability; break;
        case FaultKind::reorder: in_order *= 1.0 - s.probability; break;
        case FaultKind::delay: w.delay = std::max(w.delay, s.delay); break;
        default: break;
      }
    }
    w.drop = 1.0 - keep;
    w.corrupt = 1.0 - clean;
    w.duplicate = 1.0 - single;
    w.reorder = 1.0 - in_order;
    wire_->set(d, w);
  }
}

void FaultInjector::apply_cables() {
  network::Segment& segment = network_.segment();
  // A cable is named by the slave it leads into (Segment); a fault names it by either end.
  const auto leads_into = [&](const FaultSpec& s) {
    return segment.cabled_at(static_cast<std::size_t>(s.slave - 1), s.port);
  };
  for (std::size_t into = 0; into < network_.size(); ++into) {
    bool broken = false;
    for (const ActiveFault& f : active_)
      broken |= f.spec.kind == FaultKind::link_down && leads_into(f.spec) == static_cast<int>(into);
    if (segment.port_cable_connected(into, 0) == broken) segment.set_port_cable(into, 0, !broken);
  }
}

void FaultInjector::apply_esc(int slave) {
  esc::EscFaults e;
  for (const ActiveFault& f : active_) {
    if (f.spec.slave != slave) continue;
    switch (f.spec.kind) {
      case FaultKind::wkc_error: e.wkc_error = true; break;
      case FaultKind::sii_error: e.sii_error = true; break;
      case FaultKind::sync_lost: e.sync_lost = true; break;
      case FaultKind::watchdog: e.pd_watchdog_expired = true; break;
      default: break;
    }
  }
  network_.esc(static_cast<std::size_t>(slave - 1)).set_faults(e);
}

void FaultInjector::apply_plant(int slave) {
  plant::AxisFaults a;
  for (const ActiveFault& f : active_) {
    if (f.spec.slave != slave) continue;
    switch (f.spec.kind) {
      case FaultKind::jam: a.jam = true; break;
      case FaultKind::collision: a.obstacle = f.spec.position; break;
      case FaultKind::load_change:
        a.load_scale *= f.spec.load_scale;
        a.added_force += f.spec.force;
        a.friction_scale *= f.spec.friction_scale;
        break;
      case FaultKind::brake_failure: a.brake_failure = true; break;
      default: break;
    }
  }
  network_.firmware(static_cast<std::size_t>(slave - 1)).plant()->set_axis_faults(0, a);
}

void FaultInjector::end(std::size_t index, Nanos now) {
  const FaultSpec spec = active_[index].spec;
  active_.erase(active_.begin() + static_cast<std::ptrdiff_t>(index));
  apply_layer(spec, false, now);
}

void FaultInjector::apply_layer(const FaultSpec& spec, bool started, Nanos now) {
  switch (info(spec.kind).layer) {
    case Layer::wire: spec.kind == FaultKind::link_down ? apply_cables() : apply_wire(); break;
    case Layer::esc: apply_esc(spec.slave); break;
    case Layer::mailbox: break;
    case Layer::drive: set_drive_cause(spec, started, now); break;
    case Layer::plant: apply_plant(spec.slave); break;
  }
}

bool FaultInjector::clear(int id, Nanos now) {
  for (std::size_t i = 0; i < active_.size(); ++i) {
    if (active_[i].id == id) {
      end(i, now);
      return true;
    }
  }
  return false;
}

void FaultInjector::clear_all(Nanos now) {
  while (!active_.empty()) end(active_.size() - 1, now);
}

void FaultInjector::tick(Nanos now) {
  for (std::size_t i = 0; i < active_.size();) {
    if (active_[i].ends <= now) end(i, now);
    else ++i;
  }
}

Nanos FaultInjector::next_deadline() const {
  Nanos t = kNever;
  for (const ActiveFault& f : active_) t = std::min(t, f.ends);
  return t;
}

}  // namespace vdrive::fault
