#pragma once
// ESI export: a product as an EtherCAT Slave Information file (EtherCATInfo XML, ETG.2000), built
// from the same data the virtual drive runs on (ProductProfile + object Dictionary), so that a
// master's configurator imports exactly the slave it will find on the wire. See docs/esi.md.
#include <string>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::esi {

struct EsiOptions {
  // Panasonic ships two ESI files for the A6B (L1641-L1649): "without OD" (minimal: identity, SMs,
  // PDOs, mailbox, DC, EEPROM) and "with OD" (plus the complete object dictionary). We offer both
  // for every product; with the dictionary is the default.
  bool with_dictionary = true;
  // <Eeprom>: false = ByteSize + ConfigData (SII words 0-6) [+ BootStrap]; true = the whole SII
  // image as <Data>, for tools that program the EEPROM from the ESI.
  bool eeprom_image = false;
};

// The complete EtherCATInfo document (UTF-8, with XML declaration), one vendor, one group, one
// device. `dictionary` may be empty (then the Dictionary has no objects). Deterministic: the same
// inputs give the same bytes.
std::string export_esi(const profile::ProductProfile& profile, const od::Dictionary& dictionary,
                       const EsiOptions& options = {});

}  // namespace vdrive::esi
