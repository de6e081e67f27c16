#include "vdrive/web/slave_view.hpp"

#include "ethercat/registers.hpp"
#include "vdrive/drive/drive_engine.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::web {

std::vector<SlaveInfo> slave_infos(network::Network& network) {
  std::vector<SlaveInfo> infos;
  for (std::size_t i = 0; i < network.size(); ++i) {
    const profile::ProductProfile& p = network.profile(i);
    SlaveInfo s;
    s.position = static_cast<int>(i + 1);
    if (i < network.slave_names().size() && network.slave_names()[i] != std::to_string(i + 1)) s.name = network.slave_names()[i];
    s.product = p.id;
    s.product_name = p.title.empty() ? p.id : p.title;
    s.vendor_id = p.identity.vendor_id;
    s.product_code = p.identity.product_code;
    s.revision = p.identity.revision;
    s.drive = network.firmware(i).drive() != nullptr;
    const network::Uplink& up = network.segment().uplink(i);
    if (up.parent != network::Uplink::kMaster) {
      s.parent = up.parent + 1;
      s.parent_port = up.port;
    }
    s.profile = &p;
    infos.push_back(std::move(s));
  }
  return infos;
}

void read_registers(network::Network& network, std::vector<SlaveRegisters>& out) {
  namespace reg = ecat::reg;
  for (std::size_t i = 0; i < network.size() && i < out.size(); ++i) {
    esc::Esc& e = network.esc(i);
    SlaveRegisters& r = out[i];
    r.station_address = e.peek_u16(reg::kStationAddress);
    r.alias = e.peek_u16(reg::kStationAlias);
    r.al_status = e.peek_u16(reg::kAlStatus);
    r.al_status_code = e.peek_u16(reg::kAlStatusCode);
    for (std::uint16_t p = 0; p < 4; ++p) {
      r.rx_errors[p] = e.peek(static_cast<std::uint16_t>(reg::kRxErrorCounter + 2 * p));
      r.lost_links[p] = e.peek(static_cast<std::uint16_t>(reg::kLostLinkCounter + p));
    }
    // The DC registers live in the DC unit, which only the PDI's read path reaches; neither
    // register has a read side effect.
    std::array<std::uint8_t, 4> b{};
    e.pdi_read(reg::kDcActivation, std::span<std::uint8_t>(b.data(), 1));
    r.dc_active = (b[0] & 0x03) == 0x03;
    drive::DriveEngine* d = network.firmware(i).drive();
    r.alarm = d != nullptr ? d->alarms().newest() : nullptr;
    const firmware::SdoAbortRecord& aborts = network.firmware(i).sdo_aborts();
    r.sdo_aborts = aborts.count;
    r.abort_index = aborts.index;
    r.abort_subindex = aborts.subindex;
    r.abort_code = aborts.code;
    e.pdi_read(reg::kDcSystemTimeDifference, b);
    const std::uint32_t diff = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                               static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
    // Bit 31 set: the local copy is smaller than the received time.
    const auto magnitude = static_cast<std::int64_t>(diff & 0x7FFF'FFFFu);
    r.system_time_difference = (diff & 0x8000'0000u) != 0 ? -magnitude : magnitude;
  }
}

}  // namespace vdrive::web
