#include "vdrive/drive/modes/homing_methods.hpp"

#include <array>

namespace vdrive::drive {

namespace {

using S = HomingSwitch;
using Shape = SwitchShape;

constexpr HomingMethodSpec edge(std::int8_t m, S sw, Shape shape, bool upper, int final_dir, bool index,
                                int initial = +1, S reversal = S::None) {
  return {m, HomingKind::SwitchEdge, sw, shape, upper, final_dir, index, initial, reversal};
}

// Methods 1-14 with the index pulse; 17-30 are the same rows without it ("Same as n without Index
// Pulse", A6B L17832-L17853, DS1000A-EC L2914-L2916).
constexpr std::array<HomingMethodSpec, 14> kWithIndex = {
    // 1: away from the negative limit, first index on its positive side (A6B L18735-L18745).
    edge(1, S::NegativeLimit, Shape::ActiveBelow, true, +1, true),
    // 2: away from the positive limit, first index on its negative side (A6B L18771-L18783).
    edge(2, S::PositiveLimit, Shape::ActiveAbove, false, -1, true),
    // 3/4: home switch active above its edge; + when inactive, - when active; index on the
    // negative (3) / positive (4) side of the edge (DS1000A-EC L2807-L2811, A6B L18807-L18817).
    edge(3, S::Home, Shape::ActiveAbove, false, -1, true),
    edge(4, S::Home, Shape::ActiveAbove, false, +1, true),
    // 5/6: home switch active below its edge; - when inactive, + when active; index on the
    // positive (5) / negative (6) side (DS1000A-EC L2838-L2842).
    edge(5, S::Home, Shape::ActiveBelow, true, +1, true),
    edge(6, S::Home, Shape::ActiveBelow, true, -1, true),
    // 7-10: home switch window, positive limit beyond it; start + when inactive, reverse at the
    // limit; 7/8 start - and 9/10 start + when active (A6B L18885-L18893, DS5C1 L3598-L3600).
    // 7: index below the lower edge, 8: above the lower edge, 9: below the upper edge, 10: above it.
    edge(7, S::Home, Shape::Window, false, -1, true, +1, S::PositiveLimit),
    edge(8, S::Home, Shape::Window, false, +1, true, +1, S::PositiveLimit),
    edge(9, S::Home, Shape::Window, true, -1, true, +1, S::PositiveLimit),
    edge(10, S::Home, Shape::Window, true, +1, true, +1, S::PositiveLimit),
    // 11-14: the mirror images with the negative limit; 11/12 start + and 13/14 start - when active
    // (A6B L18948-L18956, DS5C1 L3602-L3604).
    edge(11, S::Home, Shape::Window, true, +1, true, -1, S::NegativeLimit),
    edge(12, S::Home, Shape::Window, true, -1, true, -1, S::NegativeLimit),
    edge(13, S::Home, Shape::Window, false, +1, true, -1, S::NegativeLimit),
    edge(14, S::Home, Shape::Window, false, -1, true, -1, S::NegativeLimit),
};

constexpr std::array<HomingMethodSpec, 14> without_index() {
  std::array<HomingMethodSpec, 14> rows = kWithIndex;
  for (HomingMethodSpec& r : rows) {
    r.method = static_cast<std::int8_t>(r.method + 16);
    r.index = false;
  }
  return rows;
}
constexpr std::array<HomingMethodSpec, 14> kWithoutIndex = without_index();

// 33/34: the tables print "33 On Index Pulse +Ve direction" (A6B L17856, DS5C1 L3318) but the
// DS5C1 text says 33 moves negative and 34 positive (L3667), as CiA 402 defines them: text kept.
constexpr std::array<HomingMethodSpec, 4> kOthers = {
    HomingMethodSpec{33, HomingKind::IndexOnly, S::None, Shape::ActiveBelow, false, -1, true},
    HomingMethodSpec{34, HomingKind::IndexOnly, S::None, Shape::ActiveBelow, false, +1, true},
    // 35/37: the current position is home (A6B L19289-L19332, DS1000A-EC L2928-L2934).
    HomingMethodSpec{35, HomingKind::CurrentPosition},
    HomingMethodSpec{37, HomingKind::CurrentPosition},
};

}  // namespace

const HomingMethodSpec* find_standard_homing_method(std::int8_t method) {
  if (method >= 1 && method <= 14) return &kWithIndex[static_cast<std::size_t>(method - 1)];
  if (method >= 17 && method <= 30) return &kWithoutIndex[static_cast<std::size_t>(method - 17)];
  for (const HomingMethodSpec& r : kOthers)
    if (r.method == method) return &r;
  return nullptr;
}

}  // namespace vdrive::drive
