#pragma once
// A vendor alarm code as the manuals print it, split into main and sub number:
//   A6B    "16.1"  -> main 16, sub 1   (Err16.1; 603Fh shows FF00h + main, L33944-L33948)
//   DS5C1  "E-851" -> main 85, sub 1   (the two digits after "E-" are the main number, L7371-L7378)
//   DS1000A-EC "FF80h" -> no main/sub  (the code is the 603Fh value itself, L4313-L4318)
#include <cstdint>
#include <string_view>

namespace vdrive::drive {

struct AlarmCode {
  enum class Style : std::uint8_t { Unknown, Panasonic, Xinje, Cia402 } style = Style::Unknown;
  std::uint8_t main = 0;
  std::uint8_t sub = 0;
  std::uint16_t display = 0;   // Xinje: the printed number ("E-851" -> 851); else 0
};

inline AlarmCode parse_alarm_code(std::string_view code) {
  auto digits = [](std::string_view s, unsigned& value) {
    if (s.empty()) return false;
    value = 0;
    for (const char c : s) {
      if (c < '0' || c > '9') return false;
      value = value * 10 + static_cast<unsigned>(c - '0');
    }
    return true;
  };
  AlarmCode out;
  unsigned a = 0, b = 0;
  if (code.size() == 5 && code.substr(0, 2) == "E-" && digits(code.substr(2), a)) {
    out.style = AlarmCode::Style::Xinje;
    out.main = static_cast<std::uint8_t>(a / 10);
    out.sub = static_cast<std::uint8_t>(a % 10);
    out.display = static_cast<std::uint16_t>(a);
    return out;
  }
  if (const auto dot = code.find('.'); dot != std::string_view::npos && digits(code.substr(0, dot), a) &&
                                         digits(code.substr(dot + 1), b) && a < 256 && b < 256) {
    out.style = AlarmCode::Style::Panasonic;
    out.main = static_cast<std::uint8_t>(a);
    out.sub = static_cast<std::uint8_t>(b);
    return out;
  }
  if (!code.empty() && (code.back() == 'h' || code.back() == 'H')) out.style = AlarmCode::Style::Cia402;
  return out;
}

}  // namespace vdrive::drive
