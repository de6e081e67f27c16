#pragma once
// Factory PDO configuration where the manual's object table leaves it out. A master that maps
// process data from CoE (1C12h/1C13h and the 16xxh/1Axxh it names) must find the same layout the
// SII's PDO categories announce, or the drive refuses Safe-Op with 0x001D/0x001E against a master
// that mapped from SII (SOEM does). So, from the profile's default PDOs:
//  - a mapping object whose table default maps nothing gets the profile's entries;
//  - 1C12h/1C13h whose table default assigns nothing get the PDOs the profile assigns to SM2/SM3;
//  - 1C00h (SyncManager communication types, ETG.1000.6) is added, or filled where the table
//    gives no values, from the profile's SM list.
// Table defaults the manual does give are kept. Every value written this way is marked synthesized.
#include <vector>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::od {

// `objects` sorted by index before and after. A profile PDO without a mapping object in the
// dictionary is SII-only and left alone; one whose mapping object lacks the subindexes the
// entries need throws profile::ProfileError.
void apply_default_pdo_configuration(std::vector<ObjectDesc>& objects,
                                     const profile::ProductProfile& profile);

}  // namespace vdrive::od
