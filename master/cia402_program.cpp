#include "master/cia402_program.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include <fmt/format.h>

#include "master/master.hpp"
#include "master/process_data.hpp"

namespace vdrive::master {

namespace {
constexpr std::uint32_t entry(std::uint16_t index, std::uint8_t sub, std::uint8_t bits) {
  return static_cast<std::uint32_t>(index) << 16 | static_cast<std::uint32_t>(sub) << 8 | bits;
}
constexpr std::uint32_t kOutputs[] = {entry(0x6040, 0, 16), entry(0x6060, 0, 8), entry(0x607A, 0, 32)};
constexpr std::uint32_t kInputs[] = {entry(0x6041, 0, 16), entry(0x6061, 0, 8), entry(0x6064, 0, 32),
                                     entry(0x60F4, 0, 32), entry(0x603F, 0, 16)};
constexpr std::uint16_t kPdoOut[] = {0x1600};
constexpr std::uint16_t kPdoIn[] = {0x1A00};
constexpr std::int8_t kCsp = 8;

// Neither Operation enabled, Quick stop active nor Fault reaction active: the states in which an
// ESM change is no alarm (IEC 61800-7-201 statusword patterns).
bool out_of_operation(std::uint16_t statusword) {
  const bool enabled = (statusword & 0x006F) == 0x0027, quick_stop = (statusword & 0x006F) == 0x0007,
             reacting = (statusword & 0x004F) == 0x000F;
  return !enabled && !quick_stop && !reacting;
}

}  // namespace

SineProgram::SineProgram(const SineProgramOptions& options) : options_(options) {}

void SineProgram::preop(Master& master) {
  master_ = &master;
  channels_.assign(master.slaves().size(), Channel{});
  DriveResult blank;
  blank.recover = options_.recover;
  blank.recovery = DriveRecovery(options_.recovery_bound);
  results_.assign(master.slaves().size(), blank);
  for (std::size_t i = 0; i < master.slaves().size(); ++i) {
    DriveResult& r = results_[i];
    const Slave& s = master.slaves()[i];
    r.position = s.position;
    r.station = s.station;
    r.name = s.info.name;
    if (!s.info.has_mailbox() || !(s.info.mailbox_protocols & mailbox_protocol::kCoE)) {
      r.note = "no CoE";
      continue;
    }
    try {
      SdoClient& sdo = master.sdo(i);
      if ((sdo.upload_value<std::uint32_t>(0x1000, 0) & 0xFFFF) != 402) {
        r.note = "not a CiA 402 device";
        continue;
      }
      assign_pdos(sdo, 0x1C12, {});
      assign_pdos(sdo, 0x1C13, {});
      map_pdo(sdo, 0x1600, kOutputs);
      map_pdo(sdo, 0x1A00, kInputs);
      assign_pdos(sdo, 0x1C12, kPdoOut);
      assign_pdos(sdo, 0x1C13, kPdoIn);
      r.following_window = sdo.upload_value<std::uint32_t>(0x6065, 0);
      r.amplitude = options_.amplitude;
      if (r.amplitude <= 0.0) {
        // One motor revolution in user units: (6092h feed per shaft turn) / (6091h motor turns per shaft turn).
        const double motor = sdo.upload_value<std::uint32_t>(0x6091, 1), shaft = sdo.upload_value<std::uint32_t>(0x6091, 2);
        const double feed = sdo.upload_value<std::uint32_t>(0x6092, 1), feed_rev = sdo.upload_value<std::uint32_t>(0x6092, 2);
        r.amplitude = options_.revolutions * (feed / std::max(1.0, feed_rev)) / (std::max(1.0, motor) / std::max(1.0, shaft));
      }
      channels_[i].mapped = true;
    } catch (const std::exception& e) {
      r.note = fmt::format("PDO mapping refused: {}", e.what());
    }
  }
}

void SineProgram::locate(std::span<std::uint8_t> image) {
  located_ = true;
  if (!master_) return;
  std::uint32_t start = UINT32_MAX;
  for (const Slave& s : master_->slaves()) {
    if (s.process_data.output_bytes) start = std::min(start, s.process_data.output_logical);
    if (s.process_data.input_bytes) start = std::min(start, s.process_data.input_logical);
  }
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    Channel& c = channels_[i];
    if (!c.mapped) continue;
    const SlaveProcessData& pd = master_->slaves()[i].process_data;
    const std::uint32_t out = pd.output_logical - start, in = pd.input_logical - start;
    auto rx = [&](std::uint16_t object) { return pdo_entry_offset(pd.outputs, out, object); };
    auto tx = [&](std::uint16_t object) { return pdo_entry_offset(pd.inputs, in, object); };
    const long offsets[] = {rx(0x6040), rx(0x6060), rx(0x607A), tx(0x6041),
                            tx(0x6061), tx(0x6064), tx(0x60F4), tx(0x603F)};
    for (const long o : offsets)
      if (o < 0 || static_cast<std::size_t>(o) + 4 > image.size() + 2) c.mapped = false;
    if (!c.mapped) {
      results_[i].note = "PDO mapping not in effect";
      continue;
    }
    c.cw = offsets[0], c.mode = offsets[1], c.target = offsets[2], c.status = offsets[3];
    c.mode_display = offsets[4], c.actual = offsets[5], c.following = offsets[6], c.error = offsets[7];
  }
}

void SineProgram::outputs(std::span<std::uint8_t> image) {
  if (!located_) locate(image);
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    Channel& c = channels_[i];
    if (!c.mapped) continue;
    c.now += options_.cycle;
    const std::uint16_t s = c.status_value;
    std::uint16_t cw = 0x0006;
    if (c.finished) {
      // Shutdown (transition 8) before the master leaves Op: a drive still in Operation enabled
      // or Quick stop active when the ESM changes raises A6B Err88.2 (L33851-L33875), DS5C1 E-882
      // (L7137), and stays in Fault for whoever comes next. A fault now is left for them to see.
      c.last_cw = cw;
      image_put<std::uint16_t>(image, c.cw, cw);
      image_put<std::int8_t>(image, c.mode, kCsp);
      image_put<std::int32_t>(image, c.target, c.position);
      continue;
    }
    if (!(s & 0x0008)) c.fault_since = -1;
    else if (c.fault_since < 0) c.fault_since = c.now;
    if (s & 0x0008) {
      // Fault: reset on a 0->1 edge; recovering, only after the reaction had `reset_after` to run
      // (a stop ramp, the alarm showing on the drive and in its log), as a PLC's reset logic waits.
      const bool hold = options_.recover && c.now - c.fault_since < options_.reset_after;
      cw = hold || c.last_cw == 0x0080 ? 0x0000 : 0x0080;
    } else if ((s & 0x004F) == 0x0040) cw = 0x0006;                    // switch on disabled -> shutdown
    else if ((s & 0x006F) == 0x0021) cw = 0x0007;                    // ready -> switch on
    else if ((s & 0x006F) == 0x0023 || (s & 0x006F) == 0x0027) cw = 0x000F;  // switched on -> enable
    c.last_cw = cw;
    image_put<std::uint16_t>(image, c.cw, cw);
    image_put<std::int8_t>(image, c.mode, kCsp);
    // Until enabled (and while a fault has the drive disabled), 607Ah follows 6064h (A6B
    // L16813-L16819), so the motion starts again from where the axis stands.
    std::int32_t target = c.position;
    if (c.enabled && c.enabled_at >= 0) {
      const Nanos t = c.now - c.enabled_at - options_.settle;
      if (t < 0) {
        target = c.start;
      } else {
        // 1 - cos: zero speed at the start, no step the axis could not follow.
        const double x = results_[i].amplitude * (1.0 - std::cos(2.0 * std::numbers::pi * options_.frequency_hz * 1e-9 *
                                                                 static_cast<double>(t)));
        target = c.start + static_cast<std::int32_t>(std::lround(x));
        if (c.now - c.first_enabled_at - options_.settle > options_.motion) c.finished = true;
      }
    }
    image_put<std::int32_t>(image, c.target, target);
  }
}

void SineProgram::inputs(std::span<std::uint8_t> image) {
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    Channel& c = channels_[i];
    if (!c.mapped) continue;
    DriveResult& r = results_[i];
    c.status_value = image_get<std::uint16_t>(image, c.status);
    c.position = image_get<std::int32_t>(image, c.actual);
    if (!c.finished) r.statusword = c.status_value;  // as the sine ended, not after the shutdown
    r.error_code = image_get<std::uint16_t>(image, c.error);
    const bool enabled = (c.status_value & 0x006F) == 0x0027 && image_get<std::int8_t>(image, c.mode_display) == kCsp;
    // Enabled for the first time, or again after a fault the program reset: the motion starts
    // (again) from where the axis is, so a re-enabled drive gets no step.
    if (enabled && !c.enabled) {
      c.enabled_at = c.now;
      if (c.first_enabled_at < 0) c.first_enabled_at = c.now;
      c.start = c.position;
      r.enabled = true;
    }
    c.enabled = enabled;
    if (r.enabled && (c.status_value & 0x0008)) r.faulted = true;
    // After the sine the program disables the drive itself: no outage.
    if (!c.finished) {
      const DriveRecovery::Event event = r.recovery.update(c.now, enabled, r.error_code);
      if (event != DriveRecovery::Event::none && on_recovery_) on_recovery_(r, event);
    }
    // Only while enabled: a disabled drive's 60F4h says nothing of how it follows.
    if (enabled && c.now - c.enabled_at > options_.settle && !c.finished) {
      const std::int64_t fe = std::abs(static_cast<std::int64_t>(image_get<std::int32_t>(image, c.following)));
      r.max_following_error = std::max(r.max_following_error, fe);
      ++r.samples;
    }
  }
}

void SineProgram::attach(OpRunOptions& options) {
  options.preop = [this](Master& m) { preop(m); };
  options.outputs = [this](std::span<std::uint8_t> image) { outputs(image); };
  options.inputs = [this](std::span<std::uint8_t> image) { inputs(image); };
  options.done = [this] { return done(); };
}

std::uint64_t SineProgram::cycles_needed(Nanos cycle) const {
  return static_cast<std::uint64_t>((options_.settle + options_.motion) / cycle) + 5000;
}

std::size_t SineProgram::drives() const {
  return static_cast<std::size_t>(std::count_if(channels_.begin(), channels_.end(), [](const Channel& c) { return c.mapped; }));
}

std::size_t SineProgram::enabled_now() const {
  return static_cast<std::size_t>(
      std::count_if(channels_.begin(), channels_.end(), [](const Channel& c) { return c.mapped && c.enabled; }));
}

bool SineProgram::done() const {
  bool any = false;
  for (const Channel& c : channels_) {
    if (!c.mapped) continue;
    any = true;
    if (!c.finished || !out_of_operation(c.status_value)) return false;
  }
  return any;
}

// Why a drive failed, first cause first: it never got enabled, it faulted, nothing was measured,
// or it left its window.
std::string verdict(const DriveResult& r) {
  if (r.ok()) return "ok";
  if (!r.enabled) return "FAILED (never reached Operation enabled)";
  if (r.recover && r.recovery.overdue() > 0)
    return fmt::format("FAILED (not enabled again within the bound: {} of {} outages)", r.recovery.overdue(),
                       r.recovery.outages());
  if (r.faulted) return fmt::format("FAILED (faulted, 603Fh {:04X}h)", r.error_code);
  if (r.samples == 0) return "FAILED (no sine cycle measured)";
  return fmt::format("FAILED (following error {} beyond the window {})", r.max_following_error, r.following_window);
}

// "; 3 outages, 3 recovered (603Fh FF18h x2, none x1), longest 412 ms"
static std::string outages(const DriveResult& r) {
  const DriveRecovery& d = r.recovery;
  if (!r.recover && d.outages() == 0) return "";
  std::string codes;
  for (const AlarmCount& a : d.codes()) {
    codes += codes.empty() ? " (" : ", ";
    codes += a.code != 0 ? fmt::format("603Fh {:04X}h x{}", a.code, a.count) : fmt::format("none x{}", a.count);
  }
  if (d.other_codes() > 0) codes += fmt::format(", {} others", d.other_codes());
  if (!codes.empty()) codes += ")";
  return fmt::format("; {} outages, {} recovered{}, longest {} ms{}", d.outages(), d.recoveries(), codes,
                     d.longest() / 1'000'000, d.out() ? ", out at the end" : "");
}

std::string label(const DriveResult& r) { return ecat::slave_label(r.position, r.station, r.name); }

std::string describe(const DriveResult& r) {
  return fmt::format("{}: {}, amplitude {:.0f}, max following error {} (window 6065h = {}; position "
                     "units of 6064h) over {} cycles, statusword 0x{:04X}, 603Fh 0x{:04X}{}{}{}",
                     label(r), verdict(r), r.amplitude, r.max_following_error,
                     r.following_window, r.samples, r.statusword, r.error_code, outages(r), r.note.empty() ? "" : ": ", r.note);
}

}  // namespace vdrive::master
