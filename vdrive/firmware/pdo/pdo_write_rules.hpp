#pragma once
// SDO write rules for the PDO objects (16xxh, 1Axxh, 1C12h, 1C13h), installed as ObjectStore
// write hooks. Per product (PdoLimits): writable only in the product's states (else its abort,
// A6B/DS5C1 06010003h, otherwise 08000022h); subindexes 01h+ only while 00h = 0 (06010003h);
// assignment entries must name a mapping object of their direction (06090030h); and, where the
// product judges mappings at the write rather than at PreOp->SafeOp, a non-mappable entry is
// 06040041h and a 00h that makes the PDO(s) longer than the product allows is 06040042h.
#include <cstdint>
#include <span>

#include "vdrive/firmware/al_state_machine.hpp"
#include "vdrive/firmware/pdo/pdo_limits.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::firmware::pdo {

// The decision for one write of `data` to index:subindex in `state` (Ok = let the store apply
// its own checks and store it). Writes to other objects are Ok.
od::SdoAbort judge_pdo_write(const od::ObjectStore& objects, ecat::AlState state,
                             const PdoLimits& limits, std::uint16_t index, std::uint8_t subindex,
                             std::span<const std::uint8_t> data);

// Installs judge_pdo_write() on every PDO object the dictionary has. `objects` and `esm` must
// outlive the hooks (both belong to the SlaveFirmware).
void install_pdo_write_rules(od::ObjectStore& objects, const AlStateMachine& esm,
                             const PdoLimits& limits);

}  // namespace vdrive::firmware::pdo
