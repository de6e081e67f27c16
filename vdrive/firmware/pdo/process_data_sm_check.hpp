#pragma once
// The PreOp->SafeOp check of a process-data SyncManager (SM2 outputs, SM3 inputs) against the
// mapped size, as A6B Err81.7 (L33546-L33624) and DS5C1 E-817 (L7129-L7133) describe it:
// enabled when the direction maps data; length = mapped bytes (so an SM running with a length
// while nothing is mapped is a length fault); 3-buffer mode with the right direction; start even
// and the 3-buffer footprint (3 x length) inside process RAM; no overlap with any other enabled
// SyncManager. Pure function of the SM channel registers.
#include <cstdint>
#include <span>
#include <string_view>

#include "vdrive/firmware/pdi.hpp"

namespace vdrive::firmware::pdo {

enum class PdSmFault : std::uint8_t {
  Ok,
  Disabled,          // data mapped but the SM is not enabled
  EnabledWithoutData,// nothing mapped, length 0, but the SM enabled (only with unused_must_be_disabled)
  Length,            // length != mapped bytes (also: nothing mapped but an enabled SM with a length)
  Start,             // footprint outside process RAM
  OddStart,
  Control,           // not 3-buffer, or wrong direction
  Overlap,
};

std::string_view describe(PdSmFault fault);

// `sm` carries outputs (master writes) or inputs (master reads); `sms` indexed by SM number;
// process RAM is [0x1000, ram_end); an output SM may also sit on the digital output data
// (0x0F00-0x0F03, footprint included), as a digital output terminal's does.
// With `check_mode` the control byte must select 3-buffer mode as well as the direction. With
// `unused_must_be_disabled` a direction that maps nothing wants its SM disabled even at length 0,
// which the ESC would not run anyway (profile pdo_rules.unused_sm_must_be_disabled).
PdSmFault check_process_data_sm(std::span<const SmChannel> sms, int sm, bool outputs, std::uint16_t mapped_bytes,
                                std::uint32_t ram_end, bool check_mode = true, bool unused_must_be_disabled = false);
// SM2 outputs, SM3 inputs.
inline PdSmFault check_process_data_sm(std::span<const SmChannel> sms, int sm, std::uint16_t mapped_bytes,
                                       std::uint32_t ram_end) {
  return check_process_data_sm(sms, sm, sm == 2, mapped_bytes, ram_end);
}

}  // namespace vdrive::firmware::pdo
