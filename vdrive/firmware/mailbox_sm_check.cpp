#include "vdrive/firmware/mailbox_sm_check.hpp"

#include <algorithm>

namespace vdrive::firmware {
namespace {

// Bytes of ESC memory an SM occupies: control bits 1:0 = 00 is the 3-buffer mode, which uses
// three consecutive buffers of `length` bytes; mailbox mode (10) uses one.
std::uint32_t footprint(const SmChannel& sm) {
  const bool buffered = (sm.control & ecat::reg::sm::kModeMask) == ecat::reg::sm::kModeBuffered;
  return buffered ? 3u * sm.length : sm.length;
}

bool overlap(const SmChannel& a, const SmChannel& b) {
  const std::uint32_t a_begin = a.start, a_end = a_begin + footprint(a);
  const std::uint32_t b_begin = b.start, b_end = b_begin + footprint(b);
  if (a_begin == a_end || b_begin == b_end) return false;
  return a_begin < b_end && b_begin < a_end;
}

}  // namespace

std::string_view describe(MailboxSmFault fault) {
  switch (fault) {
    case MailboxSmFault::Ok: return "ok";
    case MailboxSmFault::Sm0Disabled: return "SM0 not enabled";
    case MailboxSmFault::Sm1Disabled: return "SM1 not enabled";
    case MailboxSmFault::Sm0Length: return "SM0 length out of range";
    case MailboxSmFault::Sm1Length: return "SM1 length out of range";
    case MailboxSmFault::Sm0Start: return "SM0 start address out of range";
    case MailboxSmFault::Sm1Start: return "SM1 start address out of range";
    case MailboxSmFault::Sm0OddStart: return "SM0 start address odd";
    case MailboxSmFault::Sm1OddStart: return "SM1 start address odd";
    case MailboxSmFault::Sm0Control: return "SM0 control byte not a write mailbox";
    case MailboxSmFault::Sm1Control: return "SM1 control byte not a read mailbox";
    case MailboxSmFault::Overlap: return "mailbox SyncManagers overlap";
  }
  return "?";
}

MailboxSmFault check_mailbox_sms(std::span<const SmChannel> sms,
                                 const profile::MailboxSmRules& rules) {
  if (sms.size() < 2) return MailboxSmFault::Sm0Disabled;
  const SmChannel& sm0 = sms[0];
  const SmChannel& sm1 = sms[1];

  if (!sm0.enabled()) return MailboxSmFault::Sm0Disabled;
  if (!sm1.enabled()) return MailboxSmFault::Sm1Disabled;
  if (sm0.length < rules.sm0_min_length || sm0.length > rules.sm0_max_length)
    return MailboxSmFault::Sm0Length;
  if (sm1.length < rules.sm1_min_length || sm1.length > rules.sm1_max_length)
    return MailboxSmFault::Sm1Length;
  if (sm0.start < rules.sm0_start_min || sm0.start > rules.sm0_start_max)
    return MailboxSmFault::Sm0Start;
  if (sm1.start < rules.sm1_start_min || sm1.start > rules.sm1_start_max)
    return MailboxSmFault::Sm1Start;
  if (rules.require_even_start && (sm0.start & 1u) != 0) return MailboxSmFault::Sm0OddStart;
  if (rules.require_even_sm1_start && (sm1.start & 1u) != 0) return MailboxSmFault::Sm1OddStart;
  if ((sm0.control & rules.sm0_control_mask) != rules.sm0_control_value)
    return MailboxSmFault::Sm0Control;
  if ((sm1.control & rules.sm1_control_mask) != rules.sm1_control_value)
    return MailboxSmFault::Sm1Control;

  if (overlap(sm0, sm1)) return MailboxSmFault::Overlap;
  // The process-data SMs only count when the master has enabled them (A6B: "mailbox area
  // overlaps the SM2/3 area", L33406-L33410; DS5C1 E-811).
  for (std::size_t n = 2; n < sms.size(); ++n) {
    if (!sms[n].enabled()) continue;
    if (overlap(sm0, sms[n]) || overlap(sm1, sms[n])) return MailboxSmFault::Overlap;
  }
  return MailboxSmFault::Ok;
}

profile::MailboxSmRules boot_mailbox_rules(const profile::ProductProfile& product) {
  profile::MailboxSmRules rules = product.mailbox_rules;
  if (product.mailbox.boot_rx_size)
    rules.sm0_max_length = std::min(rules.sm0_max_length, *product.mailbox.boot_rx_size);
  if (product.mailbox.boot_tx_size)
    rules.sm1_max_length = std::min(rules.sm1_max_length, *product.mailbox.boot_tx_size);
  return rules;
}

}  // namespace vdrive::firmware
