#pragma once
// The generic CiA 402 personality: what a drive imported from an ESI file (profile 402) does where
// its file says nothing about behaviour. Its modes, homing methods and touch probe follow the
// dictionary (6502h, 6098h, 60B8h); everything else is CiA 402 / ETG.6010 practice, written out in
// docs/networks.md ("Generic personalities").
#include <vector>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::esi {

// True when the device is a CiA 402 drive the drive engine can run: profile 402 and a dictionary
// with a controlword (6040h) and a statusword (6041h).
bool is_cia402_drive(std::uint32_t profile_no, const std::vector<od::ObjectDesc>& objects);

// Fills the drive sections of `product` (modes, homing, touch_probe, drive, alarms, motors).
void apply_generic_cia402(profile::ProductProfile& product, const std::vector<od::ObjectDesc>& objects);

// The object `index` of `objects` (sorted by index), or nullptr.
const od::ObjectDesc* find_object(const std::vector<od::ObjectDesc>& objects, std::uint16_t index);
// The entry index:subindex of `objects` (sorted by index), or nullptr.
const od::EntryDesc* find_entry(const std::vector<od::ObjectDesc>& objects, std::uint16_t index, std::uint8_t subindex);
// Its default value as an unsigned integer (little-endian, at most 8 bytes); `otherwise` without one.
std::uint64_t default_of(const std::vector<od::ObjectDesc>& objects, std::uint16_t index, std::uint8_t subindex,
                         std::uint64_t otherwise);

}  // namespace vdrive::esi
