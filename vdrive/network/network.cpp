#include "vdrive/network/network.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "esc_model/sii_eeprom.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "plant/plant.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::network {
namespace {

// SII word 4 (configured station alias) and the configuration area's CRC (word 7 low byte).
void set_station_alias(std::vector<std::uint8_t>& sii, std::uint16_t alias) {
  if (sii.size() < 16) return;
  sii[8] = static_cast<std::uint8_t>(alias);
  sii[9] = static_cast<std::uint8_t>(alias >> 8);
  sii[14] = esc::sii_config_crc(std::span<const std::uint8_t>(sii).first(14));
}

// A product code and revision the product covers (Identity::covers), or std::invalid_argument.
void choose_identity(profile::ProductProfile& p, const IdentityChoice& choice, std::size_t slave) {
  if (!p.identity.covers(p.identity.vendor_id, choice.product_code))
    throw std::invalid_argument(fmt::format("slave {}: {} does not cover product code 0x{:08X} (its own is 0x{:08X}, "
                                            "mask 0x{:08X})", slave + 1, p.id, choice.product_code,
                                            p.identity.product_code, p.identity.product_code_mask));
  p.identity.product_code = choice.product_code;
  p.identity.revision = choice.revision;
}

}  // namespace

Network::Network(std::span<const std::string> product_ids, const Clock& clock,
                 const NetworkOptions& options)
    : segment_(options.hop_delay) {
  slaves_.reserve(product_ids.size());
  for (const std::string& id : product_ids) {
    auto slave = std::make_unique<Slave>();
    firmware::FirmwareOptions firmware_options;
    esc::EscConfig esc_config;
    if (esi::is_esi_reference(id)) {
      const std::shared_ptr<const esi::ImportedDevice> device = esi::load_esi_device(id);
      slave->profile = device->profile;
      esc_config = profile::make_esc_config(slave->profile);
      esc_config.sii_image = device->sii_image;
      firmware_options.dictionary = device->dictionary;
    } else {
      slave->profile = profile::load_profile(id, options.profile_dir);
      if (slaves_.size() < options.identities.size() && options.identities[slaves_.size()]) {
        choose_identity(slave->profile, *options.identities[slaves_.size()], slaves_.size());
        // Its own dictionary: 1018h reports the identity chosen.
        firmware_options.dictionary =
            std::make_shared<const od::Dictionary>(od::Dictionary::load(slave->profile, options.profile_dir));
      }
      esc_config = profile::make_esc_config(slave->profile);
    }
    if (slaves_.size() < options.station_aliases.size() && options.station_aliases[slaves_.size()])
      set_station_alias(esc_config.sii_image, *options.station_aliases[slaves_.size()]);
    slave->esc = std::make_unique<esc::Esc>(esc_config, clock);
    if (slaves_.size() < options.dc_models.size()) {
      const DcModel& dc = options.dc_models[slaves_.size()];
      slave->esc->set_dc_model(dc.drift_ppm, dc.start_offset);
    }
    if (options.foe_strict_firmware_check) slave->profile.foe_strict_firmware_check = true;
    firmware_options.profile_dir = options.profile_dir;
    if (slaves_.size() < options.plants.size()) firmware_options.plant = options.plants[slaves_.size()];
    slave->firmware = std::make_unique<firmware::SlaveFirmware>(slave->profile, *slave->esc, firmware_options);
    segment_.append(*slave->esc);
    slaves_.push_back(std::move(slave));
  }
  segment_.set_topology(options.topology);
  resolve_signals(options);
  const Nanos now = clock.now();
  for (auto& slave : slaves_) slave->firmware->power_on(now);
}

SignalAccess Network::resolve(const SignalPoint& point) {
  if (point.slave >= slaves_.size())
    throw std::invalid_argument(fmt::format("slave {} does not exist (the network has {})", point.slave + 1, slaves_.size()));
  auto who = [&] {
    const std::string position = fmt::format("{}", point.slave + 1);
    const std::string& name = point.slave < slave_names_.size() ? slave_names_[point.slave] : position;
    const std::string& id = slaves_[point.slave]->profile.id;
    return name == position ? fmt::format("slave {} ({})", position, id)
                            : fmt::format("'{}' (slave {}, {})", name, position, id);
  };
  firmware::SlaveFirmware& fw = *slaves_[point.slave]->firmware;
  if (point.plant) {
    plant::Plant* plant = fw.plant();
    if (plant == nullptr) throw std::invalid_argument(fmt::format("{} is not a drive: it has no {}", who(), connection_name(*point.plant)));
    return SignalAccess::connection(*plant, *point.plant);
  }
  od::ObjectStore& objects = fw.objects();
  const od::EntryDesc* e = objects.dictionary().find(point.index, point.subindex);
  if (e == nullptr)
    throw std::invalid_argument(fmt::format("{} has no object {:04X}h:{:02X}h", who(), point.index, point.subindex));
  try {
    return SignalAccess::entry(objects.raw(*e).data(), *e);
  } catch (const std::invalid_argument& ex) {
    throw std::invalid_argument(fmt::format("{}: {}", who(), ex.what()));
  }
}

SignalPoint Network::point_of(std::string_view name_or_point) const {
  return named_or_parsed_point(name_or_point, signals_, slave_names_);
}

SignalPoint Network::parse_point(std::string_view text) const { return parse_signal_point(text, slave_names_); }

std::string Network::format_point(const SignalPoint& point) const { return format_signal_point(point, slave_names_); }

void Network::resolve_signals(const NetworkOptions& options) {
  slave_names_.resize(slaves_.size());
  for (std::size_t i = 0; i < slaves_.size(); ++i)
    slave_names_[i] = i < options.slave_names.size() && !options.slave_names[i].empty() ? options.slave_names[i]
                                                                                           : fmt::format("{}", i + 1);
  for (const SignalWire& w : options.wires) {
    Wire wire;
    try {
      wire.from = resolve(w.from);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}: source: {}", w.name, e.what()));
    }
    try {
      wire.to = resolve(w.to);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}: target: {}", w.name, e.what()));
    }
    wire.same_entry_size = wire.from.is_entry() && wire.to.is_entry();
    if (wire.same_entry_size && wire.from.bits() != wire.to.bits())
      throw std::invalid_argument(fmt::format("{}: the source is {} bits, the target {}", w.name, wire.from.bits(),
                                              wire.to.bits()));
    wires_.push_back(wire);
  }
  for (const NamedSignal& s : options.signals) {
    try {
      signal_access_.push_back(resolve(s.point));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}{}signal '{}': {}", s.origin, s.origin.empty() ? "" : ": ", s.name, e.what()));
    }
    signals_.push_back(s);
  }
}

// Between entries whole bytes are copied; a value of fewer than 8 bits only its bits (the rest of
// the byte is the target's own). A plant connection at either end carries one bit.
void Network::copy_wires() {
  for (const Wire& w : wires_) {
    if (!w.same_entry_size) {
      w.to.write(w.from.read() != 0 ? 1 : 0);
    } else if (w.from.bits() >= 8) {
      std::memcpy(w.to.bytes(), w.from.bytes(), (w.from.bits() + 7u) / 8u);
    } else {
      const auto mask = static_cast<std::uint8_t>((1u << w.from.bits()) - 1u);
      *w.to.bytes() = static_cast<std::uint8_t>((*w.to.bytes() & ~mask) | (*w.from.bytes() & mask));
    }
  }
}

Network::~Network() = default;

void Network::power_cycle(Nanos now) {
  for (auto& slave : slaves_) {
    slave->esc->reset();
    slave->firmware->power_on(now);
  }
}

bool Network::process_frame(std::span<std::uint8_t> ethernet_frame, Nanos now) {
  const bool returns = segment_.process(ethernet_frame, now);
  // Even a destroyed frame may have changed ESC state before its error was found.
  service_irqs(now);
  return returns;
}

void Network::service_irqs(Nanos now, BetweenSlaves* between) {
  if (step_batch_ > 0) catch_up(now, between);  // what the interrupts find is the drives as of now
  for (auto& slave : slaves_) {
    if (slave->esc->pdi_irq() == 0) continue;
    slave->firmware->on_irq(now);
    if (between != nullptr) between->run();
  }
  copy_wires();
}

void Network::tick(Nanos now, BetweenSlaves* between) {
  if (step_batch_ > 0) catch_up(now, between);  // before SYNC0 is serviced, as steps on time are
  for (auto& slave : slaves_) {
    if (slave->esc->next_deadline() <= now) slave->esc->tick(now);
  }
  service_irqs(now, between);  // SYNC and watchdog events reach the firmware as IRQs
  for (auto& slave : slaves_) {
    if (slave->firmware->next_deadline() > now) continue;
    slave->firmware->tick(now);
    if (between != nullptr) between->run();
  }
  copy_wires();
}

void Network::set_control_step_batch(Nanos wait) {
  step_batch_ = wait;
  for (auto& slave : slaves_) slave->firmware->set_control_step_batch(wait);
}

// Step by step across the drives, oldest step first: a frame that arrives meanwhile overtakes
// after one drive's one step, as it does between steps on time, not after a drive's whole batch.
void Network::catch_up(Nanos now, BetweenSlaves* between) {
  bool ran = false;
  for (;;) {
    Nanos oldest = std::numeric_limits<Nanos>::max();
    for (const auto& slave : slaves_) oldest = std::min(oldest, slave->firmware->next_control_step());
    if (oldest > now) break;
    for (auto& slave : slaves_) {
      if (slave->firmware->next_control_step() > oldest) continue;
      ran = slave->firmware->step_once(now) || ran;
      if (between != nullptr) between->run();
    }
  }
  if (ran) copy_wires();  // a wire's source may be what a step changed (a drive's switch output)
}

Nanos Network::next_deadline() const {
  Nanos next = std::numeric_limits<Nanos>::max();
  for (const auto& slave : slaves_) {
    next = std::min({next, slave->esc->next_deadline(), slave->firmware->next_deadline()});
  }
  return next;
}

}  // namespace vdrive::network
