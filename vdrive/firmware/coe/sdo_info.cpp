#include "vdrive/firmware/coe/sdo_info.hpp"

#include <algorithm>
#include <limits>

#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"
#include "vdrive/od/sdo_abort.hpp"

namespace vdrive::firmware::coe {

using ecat::coe::put_coe_header;
using ecat::coe::Service;
namespace info = ecat::coe::info;

namespace {
constexpr std::uint16_t kListCounts = 0, kListAll = 1, kListRx = 2, kListTx = 3, kListBackup = 4,
                        kListSettings = 5;
constexpr std::size_t kObjectFixed = 6;   // index, data type, max subindex, object code
constexpr std::size_t kEntryFixed = 10;   // index, subindex, value info, type, bit length, access
constexpr std::size_t kUnitTypeSize = 2;

std::size_t entry_bytes(const od::EntryDesc& e) {
  return std::max<std::size_t>(1, (e.bit_length + 7u) / 8u);
}

bool any_entry(const od::ObjectDesc& o, std::uint16_t bits) {
  return std::any_of(o.entries.begin(), o.entries.end(),
                     [bits](const od::EntryDesc& e) { return (e.access & bits) != 0; });
}

// Limits of an integer entry when the dictionary gives none: the type's own range.
std::int64_t type_min(const od::EntryDesc& e) {
  if (!od::is_signed(e.type)) return 0;
  const std::size_t bits = std::min<std::size_t>(64, entry_bytes(e) * 8);
  return bits >= 64 ? std::numeric_limits<std::int64_t>::min()
                    : -(std::int64_t{1} << (bits - 1));
}
std::int64_t type_max(const od::EntryDesc& e) {
  const std::size_t bits = std::min<std::size_t>(64, entry_bytes(e) * 8);
  if (od::is_signed(e.type)) {
    return bits >= 64 ? std::numeric_limits<std::int64_t>::max()
                      : (std::int64_t{1} << (bits - 1)) - 1;
  }
  return bits >= 63 ? std::numeric_limits<std::int64_t>::max()
                    : static_cast<std::int64_t>((std::uint64_t{1} << bits) - 1);
}
}  // namespace

SdoInfo::SdoInfo(const od::Dictionary& dictionary, bool has_store)
    : dict_(dictionary), has_store_(has_store) {
  std::size_t largest = 2 + 5 * 2;  // list type 0 reply
  for (const od::ObjectDesc& o : dict_.objects()) {
    largest = std::max(largest, kObjectFixed + o.name.size());
    for (const od::EntryDesc& e : o.entries) {
      largest = std::max(largest, kEntryFixed + kUnitTypeSize + 3 * entry_bytes(e) + e.name.size());
    }
  }
  rendered_.resize(largest);
}

bool SdoInfo::in_list(const od::ObjectDesc& o, std::uint16_t list_type) const {
  switch (list_type) {
    case kListAll: return true;
    case kListRx: return any_entry(o, od::access::kRxPdoMappable);
    case kListTx: return any_entry(o, od::access::kTxPdoMappable);
    case kListBackup:
      return has_store_ && o.index != kStoreParameters && o.index != kRestoreDefaults &&
             any_entry(o, od::access::kWriteAll);
    case kListSettings:
      return o.index != kStoreParameters && o.index != kRestoreDefaults &&
             any_entry(o, od::access::kWritePreOp);
    default: return false;
  }
}

std::size_t SdoInfo::count(std::uint16_t list_type) const {
  std::size_t n = 0;
  for (const od::ObjectDesc& o : dict_.objects()) n += in_list(o, list_type) ? 1 : 0;
  return n;
}

mailbox::Outcome SdoInfo::on_request(std::span<const std::uint8_t> request,
                                     std::span<std::uint8_t> reply) {
  pending_ = Body::None;
  if (request.size() < info::kHeaderSize) {
    return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::SizeTooShort);
  }
  const auto opcode = static_cast<info::Opcode>(request[2] & 0x7F);
  const std::span<const std::uint8_t> data = request.subspan(info::kHeaderSize);
  switch (opcode) {
    case info::Opcode::GetOdListRequest: {
      if (data.size() < 2) break;
      const std::uint16_t list_type = ecat::get_le16(data, 0);
      opcode_ = info::Opcode::GetOdListResponse;
      list_type_ = list_type;
      if (list_type == kListCounts) {
        ecat::put_le16(rendered_, 0, kListCounts);
        for (std::uint16_t t = kListAll; t <= kListSettings; ++t) {
          ecat::put_le16(rendered_, 2u * t, static_cast<std::uint16_t>(count(t)));
        }
        pending_ = Body::Rendered;
        size_ = 12;
      } else if (list_type <= kListSettings) {
        pending_ = Body::OdList;
        size_ = 2 + 2 * count(list_type);
        cursor_object_ = 0;
      } else {
        return mailbox::Outcome::reply(
            error(reply, static_cast<std::uint32_t>(od::SdoAbort::UnsupportedAccess)));
      }
      break;
    }
    case info::Opcode::GetObjectDescriptionRequest: {
      if (data.size() < 2) break;
      const od::ObjectDesc* o = dict_.find(ecat::get_le16(data, 0));
      if (o == nullptr) {
        return mailbox::Outcome::reply(
            error(reply, static_cast<std::uint32_t>(od::SdoAbort::NoSuchObject)));
      }
      opcode_ = info::Opcode::GetObjectDescriptionResponse;
      size_ = render_object(*o);
      pending_ = Body::Rendered;
      break;
    }
    case info::Opcode::GetEntryDescriptionRequest: {
      if (data.size() < 4) break;
      const std::uint16_t index = ecat::get_le16(data, 0);
      if (dict_.find(index) == nullptr) {
        return mailbox::Outcome::reply(
            error(reply, static_cast<std::uint32_t>(od::SdoAbort::NoSuchObject)));
      }
      const od::EntryDesc* e = dict_.find(index, data[2]);
      if (e == nullptr) {
        return mailbox::Outcome::reply(
            error(reply, static_cast<std::uint32_t>(od::SdoAbort::NoSuchSubindex)));
      }
      opcode_ = info::Opcode::GetEntryDescriptionResponse;
      size_ = render_entry(*e, data[3]);
      pending_ = Body::Rendered;
      break;
    }
    default:
      return mailbox::Outcome::reply(
          error(reply, static_cast<std::uint32_t>(od::SdoAbort::UnknownCommand)));
  }
  if (pending_ == Body::None) {
    return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::SizeTooShort);
  }
  offset_ = 0;
  // Fragments hold a whole number of 16-bit indexes (the capacity is rounded down to even).
  const std::size_t capacity = (reply.size() - info::kHeaderSize) & ~std::size_t{1};
  const std::size_t fragments = std::max<std::size_t>(1, (size_ + capacity - 1) / capacity);
  fragments_left_ = fragments - 1;
  return mailbox::Outcome::reply(fragment(reply));
}

std::size_t SdoInfo::next_fragment(std::span<std::uint8_t> reply) {
  if (pending_ == Body::None) return 0;
  return fragment(reply);
}

std::size_t SdoInfo::fragment(std::span<std::uint8_t> reply) {
  const std::size_t capacity = (reply.size() - info::kHeaderSize) & ~std::size_t{1};
  const std::size_t n = std::min(capacity, size_ - offset_);
  put_coe_header(reply, Service::SdoInformation);
  const bool more = offset_ + n < size_;
  reply[2] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(opcode_) |
                                       (more ? info::kIncomplete : 0));
  reply[3] = 0;
  ecat::put_le16(reply, 4, static_cast<std::uint16_t>(fragments_left_));
  copy_body(offset_, reply.subspan(info::kHeaderSize, n));
  offset_ += n;
  if (fragments_left_ > 0) --fragments_left_;
  if (!more) pending_ = Body::None;
  return info::kHeaderSize + n;
}

// Copies body bytes [offset, offset + out.size()); OD-list bodies are produced by walking the
// dictionary from a cursor, since fragments are asked for in order.
void SdoInfo::copy_body(std::size_t offset, std::span<std::uint8_t> out) {
  if (pending_ == Body::Rendered) {
    std::copy_n(rendered_.begin() + static_cast<std::ptrdiff_t>(offset), out.size(), out.begin());
    return;
  }
  std::size_t i = 0;
  if (offset == 0 && !out.empty()) {
    ecat::put_le16(out, 0, list_type_);
    i = 2;
  }
  const auto objects = dict_.objects();
  while (i + 2 <= out.size() && cursor_object_ < objects.size()) {
    const od::ObjectDesc& o = objects[cursor_object_];
    ++cursor_object_;
    if (!in_list(o, list_type_)) continue;
    ecat::put_le16(out, i, o.index);
    i += 2;
  }
}

std::size_t SdoInfo::error(std::span<std::uint8_t> reply, std::uint32_t code) {
  pending_ = Body::None;
  put_coe_header(reply, Service::SdoInformation);
  reply[2] = static_cast<std::uint8_t>(info::Opcode::ErrorRequest);
  reply[3] = 0;
  ecat::put_le16(reply, 4, 0);
  ecat::put_le32(reply, info::kHeaderSize, code);
  return info::kHeaderSize + 4;
}

std::size_t SdoInfo::render_object(const od::ObjectDesc& o) {
  std::uint16_t type = 0;
  if (o.code == od::ObjectCode::Var && !o.entries.empty()) {
    type = static_cast<std::uint16_t>(o.entries.front().type);
  } else if (const od::EntryDesc* first = o.entry(1); first != nullptr) {
    type = static_cast<std::uint16_t>(first->type);  // arrays: the element type
  }
  ecat::put_le16(rendered_, 0, o.index);
  ecat::put_le16(rendered_, 2, type);
  rendered_[4] = o.max_subindex();
  rendered_[5] = static_cast<std::uint8_t>(o.code);
  std::copy(o.name.begin(), o.name.end(), rendered_.begin() + kObjectFixed);
  return kObjectFixed + o.name.size();
}

std::size_t SdoInfo::render_entry(const od::EntryDesc& e, std::uint8_t value_info) {
  const std::size_t n = entry_bytes(e);
  const bool numeric = !od::is_string(e.type);
  // Only what this entry can describe is sent, and the reply's value info says what that is.
  std::uint8_t sent = value_info & (info::kUnitType | info::kDefault);
  if (numeric) sent |= value_info & (info::kMinimum | info::kMaximum);
  ecat::put_le16(rendered_, 0, e.index);
  rendered_[2] = e.subindex;
  rendered_[3] = sent;
  ecat::put_le16(rendered_, 4, static_cast<std::uint16_t>(e.type));
  ecat::put_le16(rendered_, 6, e.bit_length);
  ecat::put_le16(rendered_, 8, e.access);
  std::size_t at = kEntryFixed;
  if (sent & info::kUnitType) {
    ecat::put_le16(rendered_, at, 0);
    at += kUnitTypeSize;
  }
  if (sent & info::kDefault) {
    std::fill_n(rendered_.begin() + static_cast<std::ptrdiff_t>(at), n, std::uint8_t{0});
    std::copy_n(e.default_value.begin(), std::min(n, e.default_value.size()),
                rendered_.begin() + static_cast<std::ptrdiff_t>(at));
    at += n;
  }
  if (sent & info::kMinimum) {
    ecat::put_le(rendered_.data() + at, static_cast<std::uint64_t>(e.min.value_or(type_min(e))), n);
    at += n;
  }
  if (sent & info::kMaximum) {
    ecat::put_le(rendered_.data() + at, static_cast<std::uint64_t>(e.max.value_or(type_max(e))), n);
    at += n;
  }
  std::copy(e.name.begin(), e.name.end(), rendered_.begin() + static_cast<std::ptrdiff_t>(at));
  return at + e.name.size();
}

}  // namespace vdrive::firmware::coe
