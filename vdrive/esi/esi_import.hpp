#pragma once
// A device of an ESI file as a product the network can serve: its ProductProfile (identity, ESC,
// SyncManagers, mailbox, PDOs and their rules, synchronisation from <Dc>, and for a CiA 402 drive
// the generic personality), its object dictionary from <Profile><Dictionary>, and its SII image:
// the file's <Eeprom><Data> when it has one, else built from the profile as for the built-in
// products. Where the file is silent, ETG defaults apply (docs/networks.md lists them).
//
// Devices are named on the command line and in network files as "FILE.xml", "FILE.xml:PRODUCT" or
// "FILE.xml:PRODUCT:REVISION" (numbers decimal or 0x hex): without a product code the file must
// hold one device. "FILE.xml#PHYSADDR" names a slave of an ENI served from the ENI alone
// (eni_slave_device.hpp).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/esi/esi_device.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::esi {

struct ImportedDevice {
  profile::ProductProfile profile;
  std::shared_ptr<const od::Dictionary> dictionary;
  std::vector<std::uint8_t> sii_image;
};

ImportedDevice import_device(const EsiDevice& device);

struct DeviceReference {
  std::string path;
  std::optional<std::uint32_t> product_code, revision;
};

// True for a name that refers to an ESI file (ends in .xml, or has ".xml:" or ".xml#" in it, any case).
bool is_esi_reference(std::string_view name);
// Throws EsiError for a malformed product code or revision.
DeviceReference parse_device_reference(std::string_view name);
// The one device of `devices` the reference names; EsiError listing the candidates otherwise.
const EsiDevice& select_device(const std::vector<EsiDevice>& devices, const DeviceReference& reference);

// Reads, selects and imports; one import per reference per process, so every slave of one device
// shares its dictionary. Thread-safe; for construction time.
std::shared_ptr<const ImportedDevice> load_esi_device(std::string_view name);

}  // namespace vdrive::esi
