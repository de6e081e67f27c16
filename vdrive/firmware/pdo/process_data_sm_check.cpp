#include "vdrive/firmware/pdo/process_data_sm_check.hpp"

namespace vdrive::firmware::pdo {

namespace {

bool active(const SmChannel& sm) { return sm.enabled() && sm.length > 0; }

// Bytes of ESC RAM an SM occupies: a 3-buffer SM reserves three buffers (ESC datasheet).
std::uint32_t footprint(const SmChannel& sm) {
  const bool mailbox = (sm.control & reg::sm::kModeMask) == reg::sm::kModeMailbox;
  return mailbox ? sm.length : 3u * sm.length;
}

bool overlaps(const SmChannel& a, const SmChannel& b) {
  const std::uint32_t a_end = a.start + footprint(a);
  const std::uint32_t b_end = b.start + footprint(b);
  return a.start < b_end && b.start < a_end;
}

}  // namespace

std::string_view describe(PdSmFault fault) {
  switch (fault) {
    case PdSmFault::Ok: return "ok";
    case PdSmFault::Disabled: return "process-data SyncManager disabled although data is mapped";
    case PdSmFault::EnabledWithoutData: return "process-data SyncManager enabled (length 0) with nothing mapped";
    case PdSmFault::Length: return "SyncManager length differs from the mapped size";
    case PdSmFault::Start: return "SyncManager buffers outside process RAM";
    case PdSmFault::OddStart: return "SyncManager start address is odd";
    case PdSmFault::Control: return "SyncManager not in 3-buffer mode with the right direction";
    case PdSmFault::Overlap: return "SyncManager overlaps another SyncManager";
  }
  return "?";
}

PdSmFault check_process_data_sm(std::span<const SmChannel> sms, int sm, bool outputs, std::uint16_t mapped_bytes,
                                std::uint32_t ram_end, bool check_mode, bool unused_must_be_disabled) {
  const auto n = static_cast<std::size_t>(sm);
  if (n >= sms.size()) return mapped_bytes > 0 ? PdSmFault::Disabled : PdSmFault::Ok;
  const SmChannel& ch = sms[n];
  if (mapped_bytes == 0) {
    // The length rule itself: 0 bytes mapped, so a running SM's length differs (A6B L33564-L33566,
    // L33602-L33604; DS5C1 L7129-L7133; the ETG SSC's CheckSmSettings). A disabled SM is not in
    // use and its length is not looked at.
    if (active(ch)) return PdSmFault::Length;
    if (unused_must_be_disabled && ch.enabled()) return PdSmFault::EnabledWithoutData;
    return PdSmFault::Ok;
  }
  if (!ch.enabled()) return PdSmFault::Disabled;
  if (ch.length != mapped_bytes) return PdSmFault::Length;
  if (ch.start % 2 != 0) return PdSmFault::OddStart;
  // Process RAM, or (outputs) the digital output data, where a digital output device's SM sits.
  const bool on_output_register = outputs && ch.start >= reg::kDigitalOutputData &&
                                  ch.start + footprint(ch) <= reg::kDigitalOutputDataEnd;
  if (!on_output_register && (ch.start < reg::kRegisterEnd || ch.start + footprint(ch) > ram_end)) return PdSmFault::Start;
  const std::uint8_t direction = outputs ? reg::sm::kDirectionEcatWrites : reg::sm::kDirectionEcatReads;
  if ((check_mode && (ch.control & reg::sm::kModeMask) != reg::sm::kModeBuffered) ||
      (ch.control & reg::sm::kDirectionMask) != direction) {
    return PdSmFault::Control;
  }
  for (std::size_t other = 0; other < sms.size(); ++other) {
    if (other == n || !active(sms[other])) continue;
    if (overlaps(ch, sms[other])) return PdSmFault::Overlap;
  }
  return PdSmFault::Ok;
}

}  // namespace vdrive::firmware::pdo
