#pragma once
// A unit as the manuals print it (Chinese for the DS5C1 and A6B tables: 指令单位/s, 0.1 圈, r (电机))
// in English, for people who read the tools' output: "command unit/s", "0.1 rev", "r (motor)".
// Symbols and SI units pass through (Ω, °, s², mN·m); full-width brackets and letters become
// plain ones. A unit with a term the table does not know keeps that term as printed.
#include <string>
#include <string_view>

namespace vdrive::od {

std::string english_units(std::string_view manual_units);

// Whether `text` still holds CJK characters (U+3000-U+9FFF, U+FF00-U+FFEF).
bool has_cjk(std::string_view text);

}  // namespace vdrive::od
