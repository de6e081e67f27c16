// Ports and loop control. DL control 0x0100 bits 8+2p..9+2p choose per port: auto (closed while
// no link), auto-close (closed at link loss, reopened only by writing DL control again), open,
// closed. DL status 0x0110 reports PDI operational, PDI watchdog, physical link per port, and per
// port whether the loop is closed and whether communication is established.
#include "esc_model/esc_impl.hpp"

namespace vdrive::esc {

namespace {
constexpr int kPorts = 4;
}  // namespace

void Esc::Impl::update_dl_status() {
  std::uint16_t s = 0;
  if (pdi_operational) s |= reg::dl_status::kPdiOperational;
  if (pdi_watchdog_ok) s |= reg::dl_status::kPdiWatchdogOk;
  for (int p = 0; p < kPorts; ++p) {
    const bool link = port_implemented(p) && links.port[p];
    if (link) s |= static_cast<std::uint16_t>(1u << (reg::dl_status::kLinkShift + p));
    if (loop_closed(p)) {
      s |= static_cast<std::uint16_t>(1u << (reg::dl_status::kLoopStatusShift + 2 * p));
    }
    if (link) s |= static_cast<std::uint16_t>(1u << (reg::dl_status::kLoopStatusShift + 2 * p + 1));
  }
  const std::uint16_t old = get16(reg::kDlStatus);
  put16(reg::kDlStatus, s);
  if (old != s) set_ecat_event(reg::ecat_event::kDlStatus, true);
}

void Esc::Impl::links_changed(const PortLinks& now) {
  for (int p = 0; p < kPorts; ++p) {
    if (!port_implemented(p) || !links.port[p] || now.port[p]) continue;
    // Link lost: counted per port (0x0310+p, saturating); an auto-close port stays closed.
    auto_closed[static_cast<std::size_t>(p)] = true;
    std::uint8_t& lost = mem[reg::kLostLinkCounter + p];
    if (lost < reg::kCounterMax) ++lost;
  }
  links = now;
  update_dl_status();
}

void Esc::Impl::dl_control_written() {
  // Rewriting DL control reopens auto-closed ports that have link again.
  for (int p = 0; p < kPorts; ++p) {
    if (links.port[p]) auto_closed[static_cast<std::size_t>(p)] = false;
  }
  update_dl_status();
}

}  // namespace vdrive::esc
