#pragma once
// An entry's access bits as `vdrive od` and the web API print them.
#include <cstdint>
#include <string>
#include <string_view>

namespace vdrive::od {

// "ro", "rw", or "rw(PreOp)" when writes are allowed in some states only.
std::string access_text(std::uint16_t access_bits);
// "rx", "tx" or "-" (not mappable).
std::string_view pdo_text(std::uint16_t access_bits);

}  // namespace vdrive::od
