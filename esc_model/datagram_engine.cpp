// Executes the datagrams of a frame as the frame passes this ESC, with the addressing and
// working-counter rules of ETG.1000.4 / the ET1100:
//   auto-increment (AP*, ARMW; also BRD/BWR/BRW): every ESC increments ADP; it acts at ADP == 0
//   configured (FP*, FRMW): ADP == station address 0x0010, or == alias 0x0012 if DL control
//                           bit 24 enables the alias
//   working counter: read +1, write +1, read-write +1 read +2 write, only if the memory path
//   accepted the access (a full/empty mailbox refuses it)
//   APRW/FPRW write at ADO + physical read/write offset (0x0108);
//   BRD/BRW OR the slave's data into the datagram; L* go through the FMMUs; ARMW/FRMW: the
//   addressed ESC reads, all others write. Reserved commands are passed on untouched.
// The frame is checked completely before anything is executed: like the silicon, which commits
// writes only for frames with a valid FCS, a malformed frame changes nothing but the RX error
// counter.
//
// Circulating frames (simplified): when the frame passes this ESC while port 0 is closed, the
// circulating bit of the first datagram is set; a frame arriving with it already set is
// destroyed. process_frame is only called for frames that entered at port 0, so a port 0
// without link cannot occur here; only the master closing port 0 through DL control counts.
#include <algorithm>

#include "esc_model/esc_impl.hpp"

namespace vdrive::esc {

namespace {
constexpr std::uint16_t kWkcRead = 1;
constexpr std::uint16_t kWkcWrite = 1;
constexpr std::uint16_t kWkcReadWriteWrite = 2;
}  // namespace

bool Esc::Impl::process_frame(std::span<std::uint8_t> pdu, const FrameTiming& frame_timing) {
  if (const std::size_t count = dlpdu_datagrams(pdu)) return execute_frame(pdu, count, frame_timing);
  const bool other_type = pdu.size() >= kEthercatHeaderSize && parse_ethercat_header(pdu).type != kFrameTypeDlpdu;
  if (other_type) return true;  // not for the ESC
  count_rx_error();             // too short, or malformed
  return false;
}

bool Esc::Impl::execute_frame(std::span<std::uint8_t> pdu, std::size_t count, const FrameTiming& frame_timing) {
  DatagramView first(pdu.subspan(kEthercatHeaderSize));
  if (port0_closed_by_master()) {
    if (first.circulating()) return false;
    first.set_circulating(true);
  }
  access_now = frame_timing.port0_rx;
  timing = &frame_timing;
  std::size_t at = kEthercatHeaderSize;
  for (std::size_t i = 0; i < count; ++i) {
    DatagramView dg(pdu.subspan(at));
    at += dg.size();
    execute(dg);
  }
  timing = nullptr;
  if (reset_pending) {
    reset_pending = false;
    power_on_reset();
  }
  return true;
}

bool Esc::Impl::addressed_configured(std::uint16_t adp) const {
  if (adp == get16(reg::kStationAddress)) return true;
  return (get32(reg::kDlControl) & reg::dl_control::kStationAliasEnable) != 0 &&
         adp == get16(reg::kStationAlias);
}

void Esc::Impl::execute(DatagramView dg) {
  // The event request is ORed into every passing datagram, addressed or not.
  dg.set_irq(static_cast<std::uint16_t>(dg.irq() |
                                        (ecat_event_request() & get16(reg::kEcatEventMask))));
  const std::span<std::uint8_t> data = dg.data();
  const std::uint16_t ado = dg.ado();
  const std::uint16_t adp = dg.adp();
  std::uint16_t add = 0;
  bool position_here = false;
  switch (static_cast<Command>(dg.command())) {
    case Command::Aprd:
    case Command::Apwr:
    case Command::Aprw:
    case Command::Armw:
    case Command::Brd:
    case Command::Bwr:
    case Command::Brw:
      position_here = adp == 0;
      dg.set_adp(static_cast<std::uint16_t>(adp + 1));
      break;
    default:
      break;
  }
  // Injected working-counter fault: the frame passes, nothing addressed here is executed.
  if (faults.wkc_error) return;
  switch (static_cast<Command>(dg.command())) {
    case Command::Aprd:
      if (position_here) add = physical_read(ado, data, false);
      break;
    case Command::Apwr:
      if (position_here) add = physical_write(ado, data);
      break;
    case Command::Aprw:
      if (position_here) add = physical_read_write(ado, data, false);
      break;
    case Command::Fprd:
      if (addressed_configured(adp)) add = physical_read(ado, data, false);
      break;
    case Command::Fpwr:
      if (addressed_configured(adp)) add = physical_write(ado, data);
      break;
    case Command::Fprw:
      if (addressed_configured(adp)) add = physical_read_write(ado, data, false);
      break;
    case Command::Brd:
      add = physical_read(ado, data, true);
      break;
    case Command::Bwr:
      add = physical_write(ado, data);
      break;
    case Command::Brw:
      add = physical_read_write(ado, data, true);
      break;
    case Command::Lrd:
      add = logical(dg.logical_address(), data, true, false);
      break;
    case Command::Lwr:
      add = logical(dg.logical_address(), data, false, true);
      break;
    case Command::Lrw:
      add = logical(dg.logical_address(), data, true, true);
      break;
    case Command::Armw:
      add = position_here ? physical_read(ado, data, false) : physical_write(ado, data);
      break;
    case Command::Frmw:
      add = addressed_configured(adp) ? physical_read(ado, data, false)
                                      : physical_write(ado, data);
      break;
    case Command::Nop:
    default:
      return;  // NOP and reserved commands: no action, no working counter
  }
  if (add != 0) dg.set_wkc(static_cast<std::uint16_t>(dg.wkc() + add));
}

std::uint16_t Esc::Impl::physical_read(std::uint16_t ado, std::span<std::uint8_t> data,
                                       bool or_data) {
  if (!or_data) return read_range(Side::Ecat, ado, data) ? kWkcRead : 0;
  const std::span<std::uint8_t> got = std::span<std::uint8_t>(scratch_out).first(data.size());
  std::fill(got.begin(), got.end(), std::uint8_t{0});
  if (!read_range(Side::Ecat, ado, got)) return 0;
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(data[i] | got[i]);
  return kWkcRead;
}

std::uint16_t Esc::Impl::physical_write(std::uint16_t ado, std::span<const std::uint8_t> data) {
  return write_range(Side::Ecat, ado, data) ? kWkcWrite : 0;
}

std::uint16_t Esc::Impl::physical_read_write(std::uint16_t ado, std::span<std::uint8_t> data,
                                             bool or_data) {
  // Read first (into a copy, so refused bytes keep the datagram's value), then write what the
  // master sent, then hand the read data back in the datagram.
  const std::span<std::uint8_t> sent = std::span<std::uint8_t>(scratch_in).first(data.size());
  const std::span<std::uint8_t> got = std::span<std::uint8_t>(scratch_out).first(data.size());
  std::copy(data.begin(), data.end(), sent.begin());
  if (or_data) {
    std::fill(got.begin(), got.end(), std::uint8_t{0});
  } else {
    std::copy(data.begin(), data.end(), got.begin());
  }
  // APRW/FPRW write at the address plus the physical read/write offset (0x0108, normally 0).
  const auto write_address =
      or_data ? ado : static_cast<std::uint16_t>(ado + get16(reg::kPhysicalRwOffset));
  const bool read_ok = read_range(Side::Ecat, ado, got);
  const bool write_ok = write_range(Side::Ecat, write_address, sent);
  if (read_ok) {
    for (std::size_t i = 0; i < data.size(); ++i) {
      data[i] = or_data ? static_cast<std::uint8_t>(data[i] | got[i]) : got[i];
    }
  }
  return static_cast<std::uint16_t>((read_ok ? kWkcRead : 0) +
                                    (write_ok ? kWkcReadWriteWrite : 0));
}

std::uint16_t Esc::Impl::logical(std::uint32_t address, std::span<std::uint8_t> data,
                                 bool do_read, bool do_write) {
  // Writes use the data as it arrived, so an LRW over overlapping read and write windows
  // (inputs and outputs at the same logical address) writes the master's outputs. Only the
  // bytes this ESC's write windows take are kept aside: on a long line the datagram is mostly
  // other slaves' data.
  std::span<const std::uint8_t> sent = data;
  if (do_read && do_write) {
    const std::span<std::uint8_t> kept = std::span<std::uint8_t>(scratch_in).first(data.size());
    for (int n = 0; n < fmmu_count; ++n) {
      std::size_t offset = 0;
      std::size_t count = 0;
      if (!fmmus[static_cast<std::size_t>(n)].written_bytes(address, data.size(), offset, count)) continue;
      std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(offset), count, kept.begin() + static_cast<std::ptrdiff_t>(offset));
    }
    sent = kept;
  }
  bool read_done = false;
  bool write_done = false;
  for (int n = 0; n < fmmu_count; ++n) {
    const Fmmu& f = fmmus[static_cast<std::size_t>(n)];
    if (do_read && f.read(address, data, *this).done) read_done = true;
    if (do_write && f.write(address, sent, *this).done) write_done = true;
  }
  std::uint16_t add = 0;
  if (read_done) add = static_cast<std::uint16_t>(add + kWkcRead);
  if (write_done) add = static_cast<std::uint16_t>(add + (do_read ? kWkcReadWriteWrite : kWkcWrite));
  return add;
}

}  // namespace vdrive::esc
