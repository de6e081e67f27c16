#include "vdrive/drive/io/input_logic.hpp"

#include "plant/plant.hpp"

namespace vdrive::drive {
namespace {

// DS1000A-EC logic objects: 0 = active-H, 1 = active-L (factory value, objects.yaml L4856-L4866).
constexpr std::uint16_t kFactoryLogic = 1;

// A6B SI input selection: one function code per byte (three control-mode bytes); EXT1 is 20h
// normally open / A0h normally closed, EXT2 21h / A1h (L24858-L24862).
bool a6b_selects(std::int32_t selection, std::uint8_t code) {
  const auto v = static_cast<std::uint32_t>(selection);
  for (int shift = 0; shift < 24; shift += 8) {
    const auto byte = static_cast<std::uint8_t>((v >> shift) & 0xFFu);
    if (byte == code || byte == (code | 0x80u)) return true;
  }
  return false;
}

}  // namespace

InputLogic::InputLogic(const DriveContext& ctx) : product_(io_product(ctx.profile)) {
  od::ObjectStore& s = ctx.objects;
  switch (product_) {
    case IoProduct::DS1000A:
      positive_limit_logic_ = ObjectRef<std::uint16_t>(s, 0x215B, 0, kFactoryLogic);
      negative_limit_logic_ = ObjectRef<std::uint16_t>(s, 0x215C, 0, kFactoryLogic);
      home_logic_ = ObjectRef<std::uint16_t>(s, 0x2162, 0, kFactoryLogic);
      break;
    case IoProduct::A6B:
      probe1_terminal_ = ObjectRef<std::int32_t>(s, 0x3404);
      probe2_terminal_ = ObjectRef<std::int32_t>(s, 0x3405);
      break;
    case IoProduct::DS5C1:
      probe1_terminal_ = ObjectRef<std::int32_t>(s, 0x253E);  // P5-62
      probe2_terminal_ = ObjectRef<std::int32_t>(s, 0x253F);  // P5-63
      break;
    case IoProduct::Generic: break;
  }
}

bool InputLogic::probe_assigned(int channel) const {
  const ObjectRef<std::int32_t>& terminal = channel == 1 ? probe1_terminal_ : probe2_terminal_;
  switch (product_) {
    case IoProduct::A6B: {
      // The dictionary carries no factory value for 3404h/3405h (the manual prints none, so the
      // store reads 0); 0 is taken as the wiring the manual asks for, EXT1 on SI5 and EXT2 on SI6.
      // Any other selection without the EXT code leaves the probe input unassigned (Err88.3).
      const std::int32_t selection = terminal.get();
      return selection == 0 || a6b_selects(selection, channel == 1 ? 0x20 : 0x21);
    }
    case IoProduct::DS5C1:
      return terminal.get() != 0;  // P5-62/P5-63 = 0: no terminal (factory value on most models, L4541)
    case IoProduct::DS1000A:
    case IoProduct::Generic: return true;
  }
  return true;
}

std::uint32_t InputLogic::detected(std::uint32_t plant_inputs) const {
  std::uint32_t out = plant_inputs;
  if (product_ == IoProduct::DS1000A) {
    // A level setting away from the factory wiring inverts what the drive detects.
    auto apply = [&out](const ObjectRef<std::uint16_t>& logic, std::uint32_t bit) {
      if ((logic.get() != 0) != (kFactoryLogic != 0)) out ^= bit;
    };
    apply(positive_limit_logic_, plant::input::positive_limit);
    apply(negative_limit_logic_, plant::input::negative_limit);
    apply(home_logic_, plant::input::home);
  }
  if (!probe_assigned(1)) out &= ~plant::input::probe1;
  if (!probe_assigned(2)) out &= ~plant::input::probe2;
  return out;
}

}  // namespace vdrive::drive
