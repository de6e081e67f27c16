#include "vdrive/firmware/pdo/copy_plan.hpp"

#include <cstring>

namespace vdrive::firmware::pdo {

namespace {

bool get_bit(const std::uint8_t* bytes, std::uint32_t bit) {
  return (bytes[bit / 8] >> (bit % 8)) & 1u;
}

void put_bit(std::uint8_t* bytes, std::uint32_t bit, bool on) {
  const auto mask = static_cast<std::uint8_t>(1u << (bit % 8));
  bytes[bit / 8] = static_cast<std::uint8_t>(on ? (bytes[bit / 8] | mask) : (bytes[bit / 8] & ~mask));
}

bool byte_aligned(std::uint32_t image_bit, std::uint16_t bits) {
  return image_bit % 8 == 0 && bits % 8 == 0;
}

}  // namespace

void CopyPlan::build(od::ObjectStore& objects, const ResolvedMapping& mapping) {
  count_ = 0;
  for (int i = 0; i < mapping.count; ++i) {
    const MappedItem& item = mapping.items[static_cast<std::size_t>(i)];
    Op op;
    op.image_bit = item.bit_offset;
    op.bits = item.bits;
    if (item.entry != nullptr) op.value = objects.raw(*item.entry).data();
    ops_[static_cast<std::size_t>(count_++)] = op;
  }
  bytes_ = mapping.bytes();
}

void CopyPlan::scatter(std::span<const std::uint8_t> image) const {
  for (int i = 0; i < count_; ++i) {
    const Op& op = ops_[static_cast<std::size_t>(i)];
    if (op.value == nullptr) continue;  // gap
    if (byte_aligned(op.image_bit, op.bits)) {
      std::memcpy(op.value, image.data() + op.image_bit / 8, op.bits / 8);
      continue;
    }
    for (std::uint16_t b = 0; b < op.bits; ++b) {
      put_bit(op.value, b, get_bit(image.data(), op.image_bit + b));
    }
  }
}

void CopyPlan::gather(std::span<std::uint8_t> image) const {
  for (int i = 0; i < count_; ++i) {
    const Op& op = ops_[static_cast<std::size_t>(i)];
    if (byte_aligned(op.image_bit, op.bits)) {
      std::uint8_t* to = image.data() + op.image_bit / 8;
      if (op.value == nullptr) {
        std::memset(to, 0, op.bits / 8);
      } else {
        std::memcpy(to, op.value, op.bits / 8);
      }
      continue;
    }
    for (std::uint16_t b = 0; b < op.bits; ++b) {
      put_bit(image.data(), op.image_bit + b, op.value != nullptr && get_bit(op.value, b));
    }
  }
}

}  // namespace vdrive::firmware::pdo
