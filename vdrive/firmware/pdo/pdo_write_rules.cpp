#include "vdrive/firmware/pdo/pdo_write_rules.hpp"

#include <algorithm>

#include "ethercat/little_endian.hpp"
#include "vdrive/firmware/pdo/pdo_mapping.hpp"

namespace vdrive::firmware::pdo {

namespace {

enum class Kind : std::uint8_t { None, Mapping, Assignment };

struct Target {
  Kind kind = Kind::None;
  Direction direction = Direction::Rx;
};

Target classify(const PdoLimits& limits, std::uint16_t index) {
  if (limits.rx.is_mapping_object(index)) return {Kind::Mapping, Direction::Rx};
  if (limits.tx.is_mapping_object(index)) return {Kind::Mapping, Direction::Tx};
  if (index == kRxAssign) return {Kind::Assignment, Direction::Rx};
  if (index == kTxAssign) return {Kind::Assignment, Direction::Tx};
  return {};
}

std::uint32_t little_endian(std::span<const std::uint8_t> data) {
  return static_cast<std::uint32_t>(ecat::get_le(data.first(std::min<std::size_t>(data.size(), 4))));
}

bool names_mapping_object(const od::ObjectStore& objects, const DirectionLimits& limits,
                          std::uint32_t value) {
  return value <= 0xFFFF && limits.is_mapping_object(static_cast<std::uint16_t>(value)) &&
         objects.dictionary().find(static_cast<std::uint16_t>(value)) != nullptr;
}

// A mapping fault found at the write, as the product answers it.
od::SdoAbort answer(const PdoLimits& limits, MappingFault fault) {
  switch (fault) {
    case MappingFault::Ok:
    case MappingFault::BadAssignment:
      return od::SdoAbort::Ok;
    case MappingFault::TooLong:
    case MappingFault::TooManyEntries:
      return limits.length_checked_on_write ? od::SdoAbort::PdoLengthExceeded : od::SdoAbort::Ok;
    case MappingFault::NoSuchObject:
    case MappingFault::NotMappable:
    case MappingFault::WrongLength:
      return limits.mappable_checked_on_write ? od::SdoAbort::NotMappable : od::SdoAbort::Ok;
  }
  return od::SdoAbort::Ok;
}

od::SdoAbort judge_mapping(const od::ObjectStore& objects, const PdoLimits& limits,
                           Direction direction, std::uint16_t index, std::uint8_t subindex,
                           std::uint32_t value) {
  const DirectionLimits& dir = limits.of(direction);
  if (subindex != 0) {
    const od::EntryDesc* desc = nullptr;
    return answer(limits,
                  check_entry(objects.dictionary(), ecat::PdoMappingEntry::decode(value), direction, desc));
  }
  if (value > dir.max_entries) return od::SdoAbort::ValueTooHigh;
  // Judge the entries 01h..value as they stand (they were written while 00h was 0).
  ResolvedMapping trial;
  return answer(limits, append_mapping_object(objects, index, static_cast<std::uint8_t>(value),
                                              direction, dir, trial));
}

od::SdoAbort judge_assignment(const od::ObjectStore& objects, const PdoLimits& limits,
                              Direction direction, std::uint16_t index, std::uint8_t subindex,
                              std::uint32_t value) {
  const DirectionLimits& dir = limits.of(direction);
  if (subindex != 0) {
    return names_mapping_object(objects, dir, value) ? od::SdoAbort::Ok
                                                     : od::SdoAbort::ValueRangeExceeded;
  }
  if (value > dir.max_assigned) return od::SdoAbort::ValueTooHigh;
  ResolvedMapping trial;
  for (std::uint32_t k = 1; k <= value; ++k) {
    const std::uint32_t mapping = read_unsigned(objects, index, static_cast<std::uint8_t>(k));
    if (!names_mapping_object(objects, dir, mapping)) return od::SdoAbort::ValueRangeExceeded;
    if (!limits.length_checked_on_write) continue;
    const auto count = static_cast<std::uint8_t>(
        read_unsigned(objects, static_cast<std::uint16_t>(mapping), 0));
    const MappingFault fault = append_mapping_object(
        objects, static_cast<std::uint16_t>(mapping), count, direction, dir, trial);
    if (fault == MappingFault::TooLong) return od::SdoAbort::PdoLengthExceeded;
  }
  return od::SdoAbort::Ok;
}

}  // namespace

od::SdoAbort judge_pdo_write(const od::ObjectStore& objects, ecat::AlState state,
                             const PdoLimits& limits, std::uint16_t index, std::uint8_t subindex,
                             std::span<const std::uint8_t> data) {
  const Target target = classify(limits, index);
  if (target.kind == Kind::None) return od::SdoAbort::Ok;
  if (!limits.writable_in(state)) return limits.wrong_state_abort;
  if (subindex != 0 && limits.sub0_must_be_zero && read_unsigned(objects, index, 0) != 0) {
    return od::SdoAbort::SubindexCannotBeWritten;
  }
  if (data.empty()) return od::SdoAbort::Ok;  // the store answers the length mismatch
  const std::uint32_t value = little_endian(data);
  if (target.kind == Kind::Mapping) {
    return judge_mapping(objects, limits, target.direction, index, subindex, value);
  }
  return judge_assignment(objects, limits, target.direction, index, subindex, value);
}

void install_pdo_write_rules(od::ObjectStore& objects, const AlStateMachine& esm,
                             const PdoLimits& limits) {
  const auto install = [&](std::uint16_t index) {
    if (objects.dictionary().find(index) == nullptr) return;
    objects.on_write(index, [&objects, &esm, limits](const od::EntryDesc& entry,
                                                    std::span<const std::uint8_t> data) {
      return judge_pdo_write(objects, esm.state(), limits, entry.index, entry.subindex, data);
    });
  };
  for (const DirectionLimits* dir : {&limits.rx, &limits.tx}) {
    for (std::uint32_t index = dir->first_index; index <= dir->last_index; ++index) {
      install(static_cast<std::uint16_t>(index));
    }
  }
  install(kRxAssign);
  install(kTxAssign);
}

}  // namespace vdrive::firmware::pdo
