#pragma once
// The objects behind an ESI device's PDOs where its file has no dictionary for them (a simple I/O
// device has no mailbox and no CoE; its PDOs are fixed, ETG.2000): the mapped entries, the mapping
// objects (16xxh/1Axxh) with the file's entries and the assignment (1C12h/1C13h) with the PDOs it
// assigns by default. The firmware then maps process data as for any device. Only objects the
// file's dictionary lacks are added, marked synthesized; nothing a master could see without CoE.
#include <vector>

#include "vdrive/esi/esi_device.hpp"
#include "vdrive/od/dictionary.hpp"

namespace vdrive::esi {

// `objects` sorted by index before and after.
void add_pdo_objects(std::vector<od::ObjectDesc>& objects, const EsiDevice& device);

}  // namespace vdrive::esi
