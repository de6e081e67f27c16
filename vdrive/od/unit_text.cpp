#include "vdrive/od/unit_text.hpp"

#include <array>
#include <utility>

namespace vdrive::od {
namespace {

// Longest first where one term holds another (指令单位 before 单位, 编码器脉冲 before 脉冲).
constexpr std::array<std::pair<std::string_view, std::string_view>, 27> kTerms = {{
    {"与触发条件有关", "depends on the trigger"},
    {"外部缩放上位", "external scaling, upper"},
    {"外部缩放下位", "external scaling, lower"},
    {"外部位移传感器", "external position sensor"},
    {"反馈尺单位", "feedback scale unit"},
    {"编码器脉冲", "encoder pulses"},
    {"编码器位置", "encoder position"},
    {"指令单位", "command unit"},
    {"指令脉冲", "command pulses"},
    {"电气角", "electrical angle"},
    {"极对数", "pole pairs"},
    {"%额定", "% rated"},
    {"额定", "rated"},
    {"周期", "cycles"},
    {"旋转", "rev"},
    {"电机", "motor"},
    {"圈", "rev"},
    {"转", "rev"},
    {"轴", "shaft"},
    {"次", "times"},
    {"分", "min"},
    {"度", "deg"},
    {"（", " ("},
    {"）", ")"},
    {"Ｎ", "N"},
    {"／", "/"},
    {"　", " "},
}};

// Decodes one UTF-8 code point at `i` (advancing it); invalid bytes count as themselves.
char32_t next_code_point(std::string_view s, std::size_t& i) {
  const auto b = static_cast<unsigned char>(s[i]);
  int extra = b >= 0xF0 ? 3 : b >= 0xE0 ? 2 : b >= 0xC0 ? 1 : 0;
  char32_t cp = extra == 3 ? b & 0x07 : extra == 2 ? b & 0x0F : extra == 1 ? b & 0x1F : b;
  ++i;
  while (extra-- > 0 && i < s.size()) cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  return cp;
}

}  // namespace

bool has_cjk(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const char32_t cp = next_code_point(text, i);
    if ((cp >= 0x3000 && cp <= 0x9FFF) || (cp >= 0xFF00 && cp <= 0xFFEF)) return true;
  }
  return false;
}

std::string english_units(std::string_view manual_units) {
  std::string out(manual_units);
  for (const auto& [term, english] : kTerms) {
    for (std::size_t at = out.find(term); at != std::string::npos; at = out.find(term, at + english.size())) {
      // "10000 指令单位/s²" keeps its space; "1指令单位" gets one between number and word.
      const bool after_digit = at > 0 && out[at - 1] >= '0' && out[at - 1] <= '9' && english.front() != ' ';
      out.replace(at, term.size(), after_digit ? " " + std::string(english) : std::string(english));
    }
  }
  std::string tidy;  // one space at most, none at either end, none before ")"
  for (const char c : out) {
    if (c == ' ' && (tidy.empty() || tidy.back() == ' ' || tidy.back() == '(')) continue;
    if (c == ')' && !tidy.empty() && tidy.back() == ' ') tidy.pop_back();
    tidy += c;
  }
  while (!tidy.empty() && tidy.back() == ' ') tidy.pop_back();
  return tidy;
}

}  // namespace vdrive::od
