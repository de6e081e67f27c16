#pragma once
// The SDO aborts a slave has answered a master with: how many, and the last one. For observers on
// the firmware's thread (the web page's event log); the SDO server keeps it, nothing reads it back.
#include <cstdint>

namespace vdrive::firmware {

struct SdoAbortRecord {
  std::uint32_t count = 0;
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::uint32_t code = 0;
};

}  // namespace vdrive::firmware
