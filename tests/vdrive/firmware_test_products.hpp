#pragma once
// The three products as the firmware tests need them, built in code from the manuals (the same
// values profiles/<id>/profile.yaml carries), so these tests do not depend on the YAML loader.
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::test {

// Standard mailbox windows; with `boot`, the bootstrap mailbox uses the same windows.
inline void set_mailbox(profile::ProductProfile& p, std::uint16_t rx_offset, std::uint16_t rx_size,
                        std::uint16_t tx_offset, std::uint16_t tx_size, bool boot) {
  p.mailbox.rx_offset = rx_offset;
  p.mailbox.rx_size = rx_size;
  p.mailbox.tx_offset = tx_offset;
  p.mailbox.tx_size = tx_size;
  if (boot) {
    p.mailbox.boot_rx_offset = rx_offset;
    p.mailbox.boot_rx_size = rx_size;
    p.mailbox.boot_tx_offset = tx_offset;
    p.mailbox.boot_tx_size = tx_size;
  }
}

// Panasonic MINAS-A6B: Err81.1 rules (L33400-L33446), Boot legal from ext. ver 7 (L33038-L33062),
// Explicit Device ID supported (L5802-L5924).
inline profile::ProductProfile a6b_product() {
  profile::ProductProfile p;
  p.id = "a6b";
  set_mailbox(p, 0x1000, 0x0100, 0x1200, 0x0100, true);
  p.mailbox.protocols = 0x000C;
  p.mailbox_rules.sm0_min_length = 32;
  p.mailbox_rules.sm0_max_length = 0xFFFF;
  p.mailbox_rules.sm1_min_length = 32;
  p.mailbox_rules.sm1_max_length = 0xFFFF;
  p.mailbox_rules.sm0_start_min = 0x1000;
  p.mailbox_rules.sm0_start_max = 0x2FFF;
  p.mailbox_rules.sm1_start_min = 0x1000;
  p.mailbox_rules.sm1_start_max = 0x2FFF;
  p.mailbox_rules.sm0_control_mask = 0x0F;
  p.mailbox_rules.sm0_control_value = 0x06;
  p.mailbox_rules.sm1_control_mask = 0x0F;
  p.mailbox_rules.sm1_control_value = 0x02;
  p.mailbox_rules.require_even_start = true;
  p.has_bootstrap = true;
  p.explicit_device_id = true;
  p.al_codes.invalid_transition = 0x0011;
  p.al_codes.unknown_state = 0x0012;
  p.al_codes.bootstrap_not_supported = 0x0013;
  p.al_codes.invalid_mailbox_config = 0x0016;
  p.al_codes.invalid_boot_mailbox_config = 0x0016;  // Err81.1 covers Init->Boot too (L33432)
  return p;
}

// Xinje DS5C1: E-811 windows (L7125), no Bootstrap (E-802, L7115), no Explicit Device ID (L2335).
inline profile::ProductProfile ds5c1_product() {
  profile::ProductProfile p;
  p.id = "ds5c1";
  set_mailbox(p, 0x1000, 0x0100, 0x1200, 0x0100, false);
  p.mailbox.protocols = 0x0004;
  p.mailbox_rules.sm0_min_length = 32;
  p.mailbox_rules.sm0_max_length = 256;
  p.mailbox_rules.sm1_min_length = 40;
  p.mailbox_rules.sm1_max_length = 256;
  p.mailbox_rules.sm0_start_min = 0x1000;
  p.mailbox_rules.sm0_start_max = 0x10FF;
  p.mailbox_rules.sm1_start_min = 0x1200;
  p.mailbox_rules.sm1_start_max = 0x12FF;
  p.mailbox_rules.sm0_control_mask = 0x3F;
  p.mailbox_rules.sm0_control_value = 0x26;
  p.mailbox_rules.sm1_control_mask = 0x3F;
  p.mailbox_rules.sm1_control_value = 0x22;
  p.mailbox_rules.require_even_start = true;
  p.has_bootstrap = false;
  p.explicit_device_id = false;
  p.al_codes.invalid_transition = 0x0011;
  p.al_codes.unknown_state = 0x0012;
  p.al_codes.bootstrap_not_supported = 0x0013;
  p.al_codes.invalid_mailbox_config = 0x0016;
  p.al_codes.invalid_boot_mailbox_config = 0;
  return p;
}

// DS1000A-EC: no ESM code table in the manual, so ETG.1000.6 codes; FoE firmware download
// (L746-L752) implies Bootstrap; rotary-switch ID via AL status code (L789-L795). SM layout is
// our own (manual has none): SM0 0x1000/128, SM1 0x1080/128, boot mailboxes the same; length
// rules are the ETG SSC defaults (34..256), as in profiles/ds1000a/profile.yaml.
inline profile::ProductProfile ds1000a_product() {
  profile::ProductProfile p;
  p.id = "ds1000a";
  set_mailbox(p, 0x1000, 0x0080, 0x1080, 0x0080, true);
  p.mailbox.protocols = 0x000C;
  p.mailbox_rules.sm0_min_length = 34;
  p.mailbox_rules.sm0_max_length = 256;
  p.mailbox_rules.sm1_min_length = 34;
  p.mailbox_rules.sm1_max_length = 256;
  p.mailbox_rules.sm0_start_min = 0x1000;
  p.mailbox_rules.sm0_start_max = 0x2FFF;
  p.mailbox_rules.sm1_start_min = 0x1000;
  p.mailbox_rules.sm1_start_max = 0x2FFF;
  p.mailbox_rules.sm0_control_mask = 0x0F;
  p.mailbox_rules.sm0_control_value = 0x06;
  p.mailbox_rules.sm1_control_mask = 0x0F;
  p.mailbox_rules.sm1_control_value = 0x02;
  p.has_bootstrap = true;
  p.explicit_device_id = true;
  p.al_codes.invalid_transition = 0x0011;
  p.al_codes.unknown_state = 0x0012;
  p.al_codes.bootstrap_not_supported = 0x0013;
  p.al_codes.invalid_mailbox_config = 0x0016;
  p.al_codes.invalid_boot_mailbox_config = 0x0015;
  return p;
}

}  // namespace vdrive::test
