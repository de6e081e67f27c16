#pragma once
// The drive's view of its synchronisation objects in the object dictionary: 1C32h/1C33h (values
// it reads at PreOp->SafeOp and the read-only values and counters it maintains), and the objects
// the profile names for the lost-sync threshold and the sync error count (A6B 3742h, 4F78h).
// Entries are looked up once at construction; an entry the product's dictionary lacks reads 0 and
// ignores writes. Reads and writes go to ObjectStore::raw (the drive updates its own read-only
// objects), allocate nothing.
#include <cstdint>

#include "vdrive/od/object_store.hpp"
#include "vdrive/firmware/sync/sync_rules.hpp"

namespace vdrive::firmware::sync {

class SyncObjects {
public:
  SyncObjects(od::ObjectStore& objects, const SyncRules& rules);

  // The values the drive computes at power-up (after the store got its defaults and stored
  // parameters): supported types, minimum cycle, calc-and-copy and delay times (from the rules),
  // counters 0. Sync type, cycle and shift time (settings) are left as the store has them.
  void load_power_on_values();

  std::uint64_t get(std::uint16_t index, std::uint8_t subindex) const;
  void set(std::uint16_t index, std::uint8_t subindex, std::uint64_t value);
  // Adds to a counter, saturating at its type's maximum.
  void count(std::uint16_t index, std::uint8_t subindex, std::uint64_t n);

private:
  const od::EntryDesc* entry(std::uint16_t index, std::uint8_t subindex) const;

  od::ObjectStore& objects_;
  const SyncRules& rules_;
};

}  // namespace vdrive::firmware::sync
