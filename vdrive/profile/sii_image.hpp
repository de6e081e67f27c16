#pragma once
// Builds a product's SII EEPROM image (ETG.1000.6 / ETG.2010 layout): ESC configuration area with
// CRC, identity, mailbox words, and the categories Strings, General, FMMU, SyncManager, (TxPDO,
// RxPDO, DC where the profile has them), ending with 0xFFFF. Also the ESC configuration for it.
#include <cstdint>
#include <vector>

#include "esc_model/esc_config.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::profile {

std::vector<std::uint8_t> build_sii_image(const ProductProfile& profile);

// ESC resources + SII image for one slave of this product.
esc::EscConfig make_esc_config(const ProductProfile& profile);

}  // namespace vdrive::profile
