#pragma once
// The precompiled copy between a process-data image (the SM2/SM3 buffer) and the object values
// it maps. Built once at PreOp->SafeOp from a ResolvedMapping; the cyclic path then only walks a
// fixed table: byte-aligned entries are memcpy, others are copied bit by bit (little-endian, LSB
// first, as EtherCAT lays out bit-mapped PDO entries). No allocation, no locks.
#include <array>
#include <cstdint>
#include <span>

#include "vdrive/firmware/pdo/pdo_mapping.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::firmware::pdo {

class CopyPlan {
public:
  // Replaces the plan with `mapping` over `objects`' value storage (which must outlive the plan).
  void build(od::ObjectStore& objects, const ResolvedMapping& mapping);
  void clear() { count_ = 0; bytes_ = 0; }

  // Image -> values (RxPDO outputs). `image` holds at least bytes().
  void scatter(std::span<const std::uint8_t> image) const;
  // Values -> image (TxPDO inputs); gaps are written as 0.
  void gather(std::span<std::uint8_t> image) const;

  std::uint16_t bytes() const { return bytes_; }
  int size() const { return count_; }

private:
  struct Op {
    std::uint8_t* value = nullptr;   // the object's value bytes (little-endian)
    std::uint32_t image_bit = 0;
    std::uint16_t bits = 0;
  };
  std::array<Op, kMaxMappedEntries> ops_{};
  int count_ = 0;
  std::uint16_t bytes_ = 0;
};

}  // namespace vdrive::firmware::pdo
