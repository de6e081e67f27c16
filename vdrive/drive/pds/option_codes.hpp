#pragma once
// The CiA 402 option codes 605Ah-605Eh (and 6007h where the product has it) as the drive applies
// them: which StopKind each command starts in each mode (A6B L26997-L27570, DS5C1 L4413-L4508 and
// L9441-L9604, DS1000A-EC L4899-L4907 with the CiA 402 meanings).
//
// A value the product does not define leaves the previous behaviour in force: the dictionary's
// range (the SDO layer refuses writes outside it), and inside it the manufacturer codes -1/-2 and
// 605Ah = 4, which the A6B and DS5C1 forbid ("下述值以外设定禁止", L27001, L4439) and the DS1000A-EC
// does not describe (CiA 402 "voltage limit": no voltage model here).
#include <cstdint>

#include "vdrive/drive/drive_context.hpp"
#include "vdrive/drive/object_ref.hpp"
#include "vdrive/drive/pds/stop_kind.hpp"

namespace vdrive::drive {

// Code -> StopKind for mode `mode` (6061h). `vendor_stop`: the product has its own servo-side stop
// for code 0 (A6B, DS5C1); without it code 0 is CiA 402 "disable drive function" (Coast).
StopKind quick_stop_kind(std::int16_t code, std::int8_t mode, bool vendor_stop);         // 605Ah
StopKind shutdown_kind(std::int16_t code, std::int8_t mode, bool vendor_stop);           // 605Bh, 605Ch
StopKind halt_kind(std::int16_t code, std::int8_t mode);                                 // 605Dh
StopKind fault_reaction_kind(std::int16_t code, std::int8_t mode, bool vendor_stop);     // 605Eh
// 605Ah 5, 6, 7 stay in Quick stop active after the stop (transition 16 possible); 0-3 go on to
// Switch on disabled (transition 12) (A6B L27009-L27021).
inline bool quick_stop_stays_active(std::int16_t code) { return code >= 5; }

class OptionCodes {
public:
  explicit OptionCodes(const DriveContext& ctx);

  // Re-reads the objects; call once per control step (no allocation, no lookup).
  void refresh();

  std::int16_t abort_connection() const { return abort_connection_.value; }   // 6007h (0 when absent)
  std::int16_t quick_stop() const { return quick_stop_.value; }               // 605Ah
  std::int16_t shutdown() const { return shutdown_.value; }                   // 605Bh
  std::int16_t disable_operation() const { return disable_operation_.value; } // 605Ch
  std::int16_t halt() const { return halt_.value; }                           // 605Dh
  std::int16_t fault_reaction() const { return fault_reaction_.value; }       // 605Eh

private:
  struct Code {
    ObjectRef<std::int16_t> ref;
    std::int16_t value = 0;       // last value the product defines
    std::uint16_t defined = 0;    // bit (code + 2) set for each code the product defines
    void refresh() {  // inline: six of these run every control step
      if (!ref.present()) return;
      const std::int16_t v = ref.get();
      if (v >= -2 && v <= 7 && (defined >> (v + 2)) & 1u) value = v;
    }
  };
  static Code make(od::ObjectStore& store, std::uint16_t index, std::uint16_t defined, std::int16_t fallback);

  Code abort_connection_, quick_stop_, shutdown_, disable_operation_, halt_, fault_reaction_;
};

}  // namespace vdrive::drive
