#include "vdrive/od/object_store.hpp"

#include <algorithm>
#include <cstring>

#include "ethercat/little_endian.hpp"

namespace vdrive::od {

namespace {

using ecat::AlState;

// The access bits that allow reading / writing in `state`. SDO runs in PreOp, SafeOp and Op; Init
// is treated as PreOp so the firmware and tools can read the dictionary before the mailbox runs.
// Boot has no CoE (ETG.1000.6: Boot carries FoE only).
std::uint16_t read_bit(AlState state) {
  switch (state) {
    case AlState::Init:
    case AlState::PreOp: return access::kReadPreOp;
    case AlState::SafeOp: return access::kReadSafeOp;
    case AlState::Op: return access::kReadOp;
    case AlState::Boot: return 0;
  }
  return 0;
}

std::uint16_t write_bit(AlState state) {
  switch (state) {
    case AlState::Init:
    case AlState::PreOp: return access::kWritePreOp;
    case AlState::SafeOp: return access::kWriteSafeOp;
    case AlState::Op: return access::kWriteOp;
    case AlState::Boot: return 0;
  }
  return 0;
}

// Bytes of a string value up to its first NUL (a visible string shorter than its capacity).
std::size_t stored_length(const EntryDesc& e, const std::uint8_t* value) {
  if (e.type != DataType::VisibleString) return e.value_bytes;
  const void* nul = std::memchr(value, 0, e.value_bytes);
  return nul ? static_cast<std::size_t>(static_cast<const std::uint8_t*>(nul) - value) : e.value_bytes;
}

// A little-endian integer of e.value_bytes bytes, sign-extended for signed types.
std::int64_t decode(const EntryDesc& e, std::span<const std::uint8_t> data) {
  std::uint64_t raw = ecat::get_le(data);
  if (is_signed(e.type) && data.size() < 8) {
    const unsigned bits = static_cast<unsigned>(8 * data.size());
    if (raw & (std::uint64_t{1} << (bits - 1))) raw |= ~std::uint64_t{0} << bits;
  }
  return static_cast<std::int64_t>(raw);
}

SdoAbort check_range(const EntryDesc& e, std::span<const std::uint8_t> data) {
  if (is_string(e.type)) return SdoAbort::Ok;
  const std::int64_t value = decode(e, data);
  if (e.max && value > *e.max) return SdoAbort::ValueTooHigh;
  if (e.min && value < *e.min) return SdoAbort::ValueTooLow;
  if (e.type == DataType::Boolean && value > 1) return SdoAbort::ValueRangeExceeded;
  // A hexadecimal digit field out of its range is refused as a whole value would be (DS5C1 App. 1.1
  // per-digit ranges, e.g. P0-09.0 0~1, L8659).
  for (const DigitField& d : e.digit_fields) {
    const auto field = static_cast<std::uint16_t>((static_cast<std::uint64_t>(value) >> d.shift) &
                                                  ((std::uint64_t{1} << d.bits) - 1));
    if (field > d.max) return SdoAbort::ValueTooHigh;
    if (field < d.min) return SdoAbort::ValueTooLow;
  }
  return SdoAbort::Ok;
}

}  // namespace

ObjectStore::ObjectStore(const Dictionary& dictionary)
    : dict_(dictionary), values_(dictionary.value_bytes()) {
  reset_to_defaults();
}

SdoAbort ObjectStore::read(std::uint16_t index, std::uint8_t subindex, std::span<std::uint8_t> out,
                           std::size_t& written, AlState state) const {
  written = 0;
  const ObjectDesc* object = dict_.find(index);
  if (!object) return SdoAbort::NoSuchObject;
  const EntryDesc* e = object->entry(subindex);
  if (!e) return SdoAbort::NoSuchSubindex;
  if (!(e->access & access::kReadAll)) return SdoAbort::WriteOnly;
  if (!(e->access & read_bit(state))) return SdoAbort::WrongState;
  const std::uint8_t* value = values_.data() + e->value_offset;
  const std::size_t size = stored_length(*e, value);
  // The caller's buffer is the mailbox's room for the value.
  if (size > out.size()) return SdoAbort::ObjectTooLong;
  std::memcpy(out.data(), value, size);
  written = size;
  return SdoAbort::Ok;
}

SdoAbort ObjectStore::write(std::uint16_t index, std::uint8_t subindex,
                            std::span<const std::uint8_t> data, AlState state) {
  const ObjectDesc* object = dict_.find(index);
  if (!object) return SdoAbort::NoSuchObject;
  const EntryDesc* e = object->entry(subindex);
  if (!e) return SdoAbort::NoSuchSubindex;
  if (!(e->access & access::kWriteAll)) return SdoAbort::ReadOnly;
  if (!(e->access & write_bit(state))) {
    // Only the PDO assignment/mapping objects are writable in some states only (objects.yaml
    // writable_in). Both products that restrict them answer 06010003h outside PreOp: A6B abort
    // table (L4411-L4552, 06010003h), DS5C1 L5587, L5622, L5652.
    return state == AlState::Boot ? SdoAbort::WrongState : SdoAbort::SubindexCannotBeWritten;
  }
  // 06070010h for every length error: the A6B lists 06070012h/06070013h as not supported
  // (L4411-L4552); the Xinje manuals document no other code.
  if (is_string(e->type) ? data.size() > e->value_bytes : data.size() != e->value_bytes)
    return SdoAbort::LengthMismatch;
  if (const SdoAbort range = check_range(*e, data); range != SdoAbort::Ok) return range;

  auto it = std::lower_bound(hooks_.begin(), hooks_.end(), index,
                             [](const auto& h, std::uint16_t i) { return h.first < i; });
  for (; it != hooks_.end() && it->first == index; ++it)
    if (const SdoAbort refused = it->second(*e, data); refused != SdoAbort::Ok) return refused;

  std::uint8_t* value = values_.data() + e->value_offset;
  std::memcpy(value, data.data(), data.size());
  // A shorter string: the rest of its room is cleared, so a read returns exactly what was written.
  std::memset(value + data.size(), 0, e->value_bytes - data.size());
  return SdoAbort::Ok;
}

void ObjectStore::on_write(std::uint16_t index, WriteHook hook) {
  // After the hooks already installed for this index: they run in installation order.
  const auto at = std::upper_bound(hooks_.begin(), hooks_.end(), index,
                                   [](std::uint16_t i, const auto& h) { return i < h.first; });
  hooks_.emplace(at, index, std::move(hook));
}

void ObjectStore::reset_to_defaults() {
  for (const ObjectDesc& o : dict_.objects()) {
    for (const EntryDesc& e : o.entries) {
      std::uint8_t* value = values_.data() + e.value_offset;
      std::memset(value, 0, e.value_bytes);
      std::memcpy(value, e.default_value.data(), std::min<std::size_t>(e.default_value.size(), e.value_bytes));
    }
  }
}

}  // namespace vdrive::od
