#pragma once
// The mailbox SyncManager check a drive runs before it opens its mailbox (Init->PreOp, Init->Boot,
// and whenever an SM activation changes while the mailbox runs). Pure function of the SM channel
// registers and the product's rules, so the same code serves the firmware and its tests.
//
// Rules (A6B Err81.1 L33400-L33446, DS5C1 E-811 L7125; data in ProductProfile::mailbox_rules):
//   SM0 and SM1 enabled; lengths within [min, max]; starts within [start_min, start_max];
//   starts even (when the product requires it); (control & mask) == value; SM0, SM1 and any
//   enabled SM2/SM3 do not overlap. A buffered (3-buffer) SM occupies 3 x length bytes of ESC RAM
//   (ESC datasheet, SyncManager chapter), so overlap uses the real footprint.
#include <cstdint>
#include <span>
#include <string_view>

#include "vdrive/firmware/pdi.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware {

// Which rule failed first, in the order checked. Only Ok lets the transition proceed.
enum class MailboxSmFault : std::uint8_t {
  Ok,
  Sm0Disabled,
  Sm1Disabled,
  Sm0Length,
  Sm1Length,
  Sm0Start,
  Sm1Start,
  Sm0OddStart,
  Sm1OddStart,
  Sm0Control,
  Sm1Control,
  Overlap,
};

std::string_view describe(MailboxSmFault fault);

// `sms` holds the SyncManager channels the ESC has (index = SM number; at least SM0 and SM1).
MailboxSmFault check_mailbox_sms(std::span<const SmChannel> sms,
                                 const profile::MailboxSmRules& rules);

// The rules for the bootstrap mailbox: the product's mailbox rules with the maximum lengths
// capped at the boot mailbox sizes the product declares (its boot loader has no bigger buffer).
profile::MailboxSmRules boot_mailbox_rules(const profile::ProductProfile& product);

}  // namespace vdrive::firmware
