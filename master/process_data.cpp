#include "master/process_data.hpp"

#include <fmt/format.h>

#include <array>

#include "master/master.hpp"
#include "master/registers.hpp"

namespace vdrive::master {

namespace {
constexpr std::uint16_t kRxPdoAssign = 0x1C12;   // SM2 (outputs)
constexpr std::uint16_t kTxPdoAssign = 0x1C13;   // SM3 (inputs)
constexpr std::uint8_t kSmOutputs = 2, kSmInputs = 3;
constexpr std::uint8_t kSiiSmOutputs = 3, kSiiSmInputs = 4;  // SII SyncManager category types
// Defaults when the SII has no SyncManager category entry for SM2/SM3 (3-buffer mode; outputs
// with ECAT write and PDI IRQ, inputs with ECAT read).
constexpr std::uint8_t kSmControlOutputs = 0x64, kSmControlInputs = 0x20;

std::uint16_t bytes_for(const std::vector<PdoMapping>& pdos) {
  std::uint32_t bits = 0;
  for (const PdoMapping& p : pdos) bits += p.bits();
  return static_cast<std::uint16_t>((bits + 7) / 8);
}

std::vector<PdoMapping> read_assignment(SdoClient& sdo, std::uint16_t assign) {
  std::vector<PdoMapping> out;
  const auto count = sdo.upload_value<std::uint8_t>(assign, 0);
  for (std::uint8_t i = 1; i <= count; ++i) {
    PdoMapping pdo;
    pdo.pdo = sdo.upload_value<std::uint16_t>(assign, i);
    const auto entries = sdo.upload_value<std::uint8_t>(pdo.pdo, 0);
    for (std::uint8_t e = 1; e <= entries; ++e) pdo.entries.push_back(sdo.upload_value<std::uint32_t>(pdo.pdo, e));
    out.push_back(std::move(pdo));
  }
  return out;
}

void write_list(SdoClient& sdo, std::uint16_t object, std::size_t count, auto&& write_entry) {
  sdo.download_value<std::uint8_t>(object, 0, 0);
  for (std::size_t i = 0; i < count; ++i) write_entry(static_cast<std::uint8_t>(i + 1), i);
  sdo.download_value<std::uint8_t>(object, 0, static_cast<std::uint8_t>(count));
}
}  // namespace

std::uint32_t PdoMapping::bits() const {
  std::uint32_t sum = 0;
  for (std::uint32_t e : entries) sum += e & 0xFF;
  return sum;
}

void read_pdo_configuration(SdoClient& sdo, SlaveProcessData& out) {
  out.outputs = read_assignment(sdo, kRxPdoAssign);
  out.inputs = read_assignment(sdo, kTxPdoAssign);
  out.from_coe = true;
}

namespace {
// The SyncManager the SII declares for outputs (type 3) or inputs (4): SM2/SM3 on a slave with a
// mailbox, SM0/SM1 on simple I/O; `fallback` when the SII has none.
std::uint8_t process_data_sm(const SlaveInfo& info, std::uint8_t type, std::uint8_t fallback) {
  for (std::size_t n = 0; n < info.sync_managers.size(); ++n)
    if (info.sync_managers[n].type == type) return static_cast<std::uint8_t>(n);
  return fallback;
}
}  // namespace

void sii_pdo_configuration(const SlaveInfo& info, SlaveProcessData& out) {
  auto take = [](const std::vector<SiiPdo>& pdos, std::uint8_t sm) {
    std::vector<PdoMapping> list;
    for (const SiiPdo& p : pdos) {
      if (p.sync_manager != sm) continue;
      PdoMapping m{p.index, {}};
      for (const SiiPdoEntry& e : p.entries) {
        m.entries.push_back((static_cast<std::uint32_t>(e.index) << 16) | (static_cast<std::uint32_t>(e.subindex) << 8) |
                            e.bit_length);
      }
      list.push_back(std::move(m));
    }
    return list;
  };
  out.outputs = take(info.rx_pdos, process_data_sm(info, kSiiSmOutputs, kSmOutputs));
  out.inputs = take(info.tx_pdos, process_data_sm(info, kSiiSmInputs, kSmInputs));
  out.from_coe = false;
}

void assign_pdos(SdoClient& sdo, std::uint16_t assign_object, std::span<const std::uint16_t> pdos) {
  write_list(sdo, assign_object, pdos.size(),
             [&](std::uint8_t sub, std::size_t i) { sdo.download_value<std::uint16_t>(assign_object, sub, pdos[i]); });
}

void map_pdo(SdoClient& sdo, std::uint16_t pdo, std::span<const std::uint32_t> entries) {
  write_list(sdo, pdo, entries.size(),
             [&](std::uint8_t sub, std::size_t i) { sdo.download_value<std::uint32_t>(pdo, sub, entries[i]); });
}

namespace {
void write_sm(Transport& t, const Slave& s, std::uint8_t n, std::uint16_t start, std::uint16_t length,
              std::uint8_t control) {
  const auto base = static_cast<std::uint16_t>(reg::kSm0 + n * reg::kSmSize);
  const std::uint8_t enable = length ? reg::kSmActivateEnable : 0;
  const std::array<std::uint8_t, 8> regs{static_cast<std::uint8_t>(start), static_cast<std::uint8_t>(start >> 8),
                                         static_cast<std::uint8_t>(length), static_cast<std::uint8_t>(length >> 8),
                                         control, 0x00, enable, 0x00};
  // Disabled first: an ESC ignores start/length/control while the SM is enabled.
  const Wkc off = t.fpwr_value<std::uint8_t>(s.station, static_cast<std::uint16_t>(base + reg::kSmActivateOffset), 0);
  const Wkc on = t.fpwr(s.station, base, regs);
  if (!off || *off != 1 || !on || *on != 1) {
    throw MasterError(fmt::format("slave {}: FPWR SM{} not taken", s.position + 1, n));
  }
}

void write_fmmu(Transport& t, const Slave& s, std::uint8_t n, std::uint32_t logical, std::uint16_t length,
                std::uint16_t physical, std::uint8_t type) {
  std::array<std::uint8_t, reg::kFmmuSize> f{};
  for (int i = 0; i < 4; ++i) f[i] = static_cast<std::uint8_t>(logical >> (8 * i));
  f[4] = static_cast<std::uint8_t>(length);
  f[5] = static_cast<std::uint8_t>(length >> 8);
  f[6] = 0;     // logical start bit
  f[7] = 7;     // logical stop bit
  f[8] = static_cast<std::uint8_t>(physical);
  f[9] = static_cast<std::uint8_t>(physical >> 8);
  f[10] = 0;    // physical start bit
  f[11] = type;
  f[12] = length ? 1 : 0;  // activate
  const Wkc wkc = t.fpwr(s.station, static_cast<std::uint16_t>(reg::kFmmu0 + n * reg::kFmmuSize), f);
  if (!wkc || *wkc != 1) throw MasterError(fmt::format("slave {}: FPWR FMMU{} not taken", s.position + 1, n));
}
}  // namespace

ProcessImageLayout configure_process_data(Master& master, std::vector<std::string>* notes) {
  ProcessImageLayout layout;
  auto& slaves = master.slaves();
  for (std::size_t i = 0; i < slaves.size(); ++i) {
    Slave& s = slaves[i];
    s.process_data = {};
    bool done = false;
    if (s.info.has_mailbox() && (s.info.mailbox_protocols & mailbox_protocol::kCoE)) {
      try {
        read_pdo_configuration(master.sdo(i), s.process_data);
        done = true;
      } catch (const std::exception& e) {
        if (notes) notes->push_back(fmt::format("slave {}: PDOs from the SII ({})", i + 1, e.what()));
      }
    }
    // As SOEM does: a CoE slave that assigns nothing to SM2 and SM3 is mapped from its SII.
    if (done && s.process_data.outputs.empty() && s.process_data.inputs.empty() &&
        (!s.info.rx_pdos.empty() || !s.info.tx_pdos.empty())) {
      if (notes) notes->push_back(fmt::format("slave {}: 1C12h/1C13h assign no PDOs; PDOs from the SII", i));
      done = false;
    }
    if (!done) sii_pdo_configuration(s.info, s.process_data);
    s.process_data.output_bytes = bytes_for(s.process_data.outputs);
    s.process_data.input_bytes = bytes_for(s.process_data.inputs);
    layout.output_bytes += s.process_data.output_bytes;
    layout.input_bytes += s.process_data.input_bytes;
    layout.expected_wkc = static_cast<std::uint16_t>(layout.expected_wkc + s.process_data.expected_wkc());
  }
  std::uint32_t out_at = layout.logical_start;
  std::uint32_t in_at = layout.logical_start + layout.output_bytes;
  for (Slave& s : slaves) {
    SlaveProcessData& pd = s.process_data;
    auto sii_sm = [&](std::uint8_t n, std::uint16_t fallback_start, std::uint8_t fallback_control) {
      if (n < s.info.sync_managers.size()) return std::pair{s.info.sync_managers[n].start, s.info.sync_managers[n].control};
      return std::pair{fallback_start, fallback_control};
    };
    const std::uint8_t out_sm = process_data_sm(s.info, kSiiSmOutputs, kSmOutputs);
    const std::uint8_t in_sm = process_data_sm(s.info, kSiiSmInputs, kSmInputs);
    const auto [out_start, out_control] = sii_sm(out_sm, 0x1100, kSmControlOutputs);
    const auto [in_start, in_control] = sii_sm(in_sm, 0x1400, kSmControlInputs);
    pd.sm2_start = out_start;
    pd.sm3_start = in_start;
    pd.output_logical = out_at;
    pd.input_logical = in_at;
    write_sm(master.transport(), s, out_sm, out_start, pd.output_bytes, out_control);
    write_sm(master.transport(), s, in_sm, in_start, pd.input_bytes, in_control);
    write_fmmu(master.transport(), s, 0, out_at, pd.output_bytes, out_start, reg::kFmmuTypeWrite);
    write_fmmu(master.transport(), s, 1, in_at, pd.input_bytes, in_start, reg::kFmmuTypeRead);
    layout.slaves.push_back({out_at, pd.output_bytes, in_at, pd.input_bytes});
    out_at += pd.output_bytes;
    in_at += pd.input_bytes;
  }
  return layout;
}

long pdo_entry_offset(const std::vector<PdoMapping>& pdos, std::uint32_t base, std::uint16_t object) {
  std::uint32_t bit = 0;
  for (const PdoMapping& p : pdos)
    for (const std::uint32_t e : p.entries) {
      if ((e >> 16) == object && (e & 0xFF00) == 0) return static_cast<long>(base + bit / 8);
      bit += e & 0xFF;
    }
  return -1;
}

}  // namespace vdrive::master
