// Synchronisation objects over the ObjectStore; see sync_objects.hpp.
#include "vdrive/firmware/sync/sync_objects.hpp"

#include <algorithm>
#include <utility>

#include "ethercat/little_endian.hpp"

namespace vdrive::firmware::sync {

SyncObjects::SyncObjects(od::ObjectStore& objects, const SyncRules& rules)
    : objects_(objects), rules_(rules) {}

const od::EntryDesc* SyncObjects::entry(std::uint16_t index, std::uint8_t subindex) const {
  return objects_.dictionary().find(index, subindex);
}

std::uint64_t SyncObjects::get(std::uint16_t index, std::uint8_t subindex) const {
  const od::EntryDesc* e = entry(index, subindex);
  if (e == nullptr) return 0;
  const std::span<const std::uint8_t> bytes = std::as_const(objects_).raw(*e);
  return ecat::get_le(bytes);
}

void SyncObjects::set(std::uint16_t index, std::uint8_t subindex, std::uint64_t value) {
  const od::EntryDesc* e = entry(index, subindex);
  if (e == nullptr) return;
  const std::span<std::uint8_t> bytes = objects_.raw(*e);
  ecat::put_le(bytes.first(std::min<std::size_t>(bytes.size(), 8)), value);
}

void SyncObjects::count(std::uint16_t index, std::uint8_t subindex, std::uint64_t n) {
  const od::EntryDesc* e = entry(index, subindex);
  if (e == nullptr || n == 0) return;
  const std::size_t bytes = std::min<std::size_t>(objects_.raw(*e).size(), 8);
  const std::uint64_t max = bytes >= 8 ? ~std::uint64_t{0} : (std::uint64_t{1} << (8 * bytes)) - 1;
  const std::uint64_t v = get(index, subindex);
  set(index, subindex, max - v < n ? max : v + n);
}

void SyncObjects::load_power_on_values() {
  const profile::SyncSpec& spec = rules_.spec;
  for (const std::uint16_t index : {kOutputSync, kInputSync}) {
    const profile::SyncObjectSpec& o = index == kOutputSync ? spec.sm2 : spec.sm3;
    if (const od::ObjectDesc* object = objects_.dictionary().find(index))
      set(index, 0, object->max_subindex());   // 20h: "Number of sub-objects"
    // 01h-03h are settings: their power-up values are the dictionary's defaults or what the
    // parameter store restored (A6B keeps 1C32h-01h/02h in EEPROM), never overwritten here.
    set(index, sub::kSupportedTypes, o.supported_sync_types);
    set(index, sub::kMinCycleTime, o.min_cycle_time_ns);
    set(index, sub::kCalcAndCopyTime, o.calc_and_copy_time_ns);
    set(index, sub::kDelayTime, o.delay_time_ns);
    set(index, sub::kSync0CycleTime, 0);
    if (rules_.spec.sm_event_missed_subindex != 0) set(index, rules_.spec.sm_event_missed_subindex, 0);
    if (rules_.spec.cycle_too_small_subindex != 0) set(index, rules_.spec.cycle_too_small_subindex, 0);
    set(index, sub::kSyncError, 0);
  }
  if (rules_.spec.sync_error_count_object != 0) set(rules_.spec.sync_error_count_object, 0, 0);
}

}  // namespace vdrive::firmware::sync
