#include "vdrive/drive/pds/option_codes.hpp"

namespace vdrive::drive {

namespace {

constexpr std::uint16_t bits(std::initializer_list<int> codes) {
  std::uint16_t b = 0;
  for (const int c : codes) b = static_cast<std::uint16_t>(b | (1u << (c + 2)));
  return b;
}

// The codes the manuals define (A6B L26581-L26591, L27005-L27057, L27161-L27211, L27308-L27328,
// L27418-L27442, L27538-L27570; DS5C1 L4420-L4502).
constexpr std::uint16_t kAbortConnection = bits({0, 1, 2, 3});
constexpr std::uint16_t kQuickStop = bits({0, 1, 2, 3, 5, 6, 7});
constexpr std::uint16_t kShutdown = bits({0, 1});
constexpr std::uint16_t kHalt = bits({1, 2, 3});
constexpr std::uint16_t kFaultReaction = bits({0, 1, 2});

// Code 0 of 605Ah/605Bh/605Ch/605Eh: the vendor's servo-side sequence, or CiA 402 "disable drive".
StopKind code_zero(bool vendor_stop) { return vendor_stop ? StopKind::DriveSide : StopKind::Coast; }

}  // namespace

StopKind quick_stop_kind(std::int16_t code, std::int8_t mode, bool vendor_stop) {
  const bool torque = is_torque_mode(mode);
  switch (code) {
    case 0: return code_zero(vendor_stop);
    case 1: case 5: return StopKind::SlowDown;        // 6084h (hm 609Ah; tq/cst 6087h)
    case 2: case 6: return StopKind::QuickStopRamp;   // 6085h (tq/cst 6087h)
    case 3: case 7: return torque ? StopKind::ZeroTorque : StopKind::CurrentLimit;  // 60C6h; tq/cst torque 0
    default: return StopKind::QuickStopRamp;          // not reached: OptionCodes only passes defined codes
  }
}

StopKind shutdown_kind(std::int16_t code, std::int8_t /*mode*/, bool vendor_stop) {
  return code == 0 ? code_zero(vendor_stop) : StopKind::SlowDown;  // 1: 6084h (hm 609Ah, tq/cst 6087h)
}

StopKind halt_kind(std::int16_t code, std::int8_t mode) {
  switch (code) {
    case 2: return StopKind::QuickStopRamp;  // 6085h (tq/cst 6087h)
    case 3: return is_torque_mode(mode) ? StopKind::ZeroTorque : StopKind::CurrentLimit;  // 6072h + 60C6h
    default: return StopKind::SlowDown;      // 1: 6084h (hm 609Ah, tq/cst 6087h)
  }
}

StopKind fault_reaction_kind(std::int16_t code, std::int8_t /*mode*/, bool vendor_stop) {
  switch (code) {
    case 1: return StopKind::SlowDown;       // 6084h (hm 609Ah, tq/cst 6087h)
    case 2: return StopKind::QuickStopRamp;  // 6085h (tq/cst 6087h)
    default: return code_zero(vendor_stop);  // 0: 3510h / P0-29 "sequence at alarm"
  }
}

OptionCodes::Code OptionCodes::make(od::ObjectStore& store, std::uint16_t index, std::uint16_t defined,
                                    std::int16_t fallback) {
  Code c{ObjectRef<std::int16_t>(store, index), fallback, defined};
  if (const od::EntryDesc* e = c.ref.entry()) {
    // Only what the product's own range admits (DS5C1 605Ah 0-7 has no -1/-2, L4419).
    for (int code = -2; code <= 7; ++code)
      if ((e->min && code < *e->min) || (e->max && code > *e->max))
        c.defined = static_cast<std::uint16_t>(c.defined & ~(1u << (code + 2)));
  }
  c.refresh();
  return c;
}

OptionCodes::OptionCodes(const DriveContext& ctx)
    : abort_connection_(make(ctx.objects, 0x6007, kAbortConnection, 0)),
      quick_stop_(make(ctx.objects, 0x605A, kQuickStop, 2)),
      shutdown_(make(ctx.objects, 0x605B, kShutdown, 0)),
      disable_operation_(make(ctx.objects, 0x605C, kShutdown, 0)),
      halt_(make(ctx.objects, 0x605D, kHalt, 1)),
      fault_reaction_(make(ctx.objects, 0x605E, kFaultReaction, 0)) {}

void OptionCodes::refresh() {
  abort_connection_.refresh();
  quick_stop_.refresh();
  shutdown_.refresh();
  disable_operation_.refresh();
  halt_.refresh();
  fault_reaction_.refresh();
}

}  // namespace vdrive::drive
