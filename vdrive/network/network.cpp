#include "vdrive/network/network.hpp"

#include <algorithm>
#include <limits>

#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/profile/sii_image.hpp"

namespace vdrive::network {

Network::Network(std::span<const std::string> product_ids, const Clock& clock,
                 const NetworkOptions& options)
    : segment_(options.hop_delay) {
  slaves_.reserve(product_ids.size());
  for (const std::string& id : product_ids) {
    auto slave = std::make_unique<Slave>();
    slave->profile = profile::load_profile(id, options.profile_dir);
    slave->esc = std::make_unique<esc::Esc>(profile::make_esc_config(slave->profile), clock);
    if (slaves_.size() < options.dc_models.size()) {
      const DcModel& dc = options.dc_models[slaves_.size()];
      slave->esc->set_dc_model(dc.drift_ppm, dc.start_offset);
    }
    firmware::FirmwareOptions firmware_options;
    firmware_options.profile_dir = options.profile_dir;
    if (slaves_.size() < options.plants.size()) firmware_options.plant = options.plants[slaves_.size()];
    slave->firmware = std::make_unique<firmware::SlaveFirmware>(slave->profile, *slave->esc, firmware_options);
    segment_.append(*slave->esc);
    slaves_.push_back(std::move(slave));
  }
  segment_.set_topology(options.topology);
  const Nanos now = clock.now();
  for (auto& slave : slaves_) slave->firmware->power_on(now);
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
  for (auto& slave : slaves_) {
    if (slave->esc->pdi_irq() == 0) continue;
    slave->firmware->on_irq(now);
    if (between != nullptr) between->run();
  }
}

void Network::tick(Nanos now, BetweenSlaves* between) {
  for (auto& slave : slaves_) {
    if (slave->esc->next_deadline() <= now) slave->esc->tick(now);
  }
  service_irqs(now, between);  // SYNC and watchdog events reach the firmware as IRQs
  for (auto& slave : slaves_) {
    if (slave->firmware->next_deadline() > now) continue;
    slave->firmware->tick(now);
    if (between != nullptr) between->run();
  }
}

Nanos Network::next_deadline() const {
  Nanos next = std::numeric_limits<Nanos>::max();
  for (const auto& slave : slaves_) {
    next = std::min({next, slave->esc->next_deadline(), slave->firmware->next_deadline()});
  }
  return next;
}

}  // namespace vdrive::network
