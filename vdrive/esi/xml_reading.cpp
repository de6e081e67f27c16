#include "vdrive/esi/xml_reading.hpp"

#include <fmt/core.h>

#include <cctype>
#include <charconv>
#include <cstring>

namespace vdrive::esi {

void XmlReading::fail(const tinyxml2::XMLElement* at, const std::string& what) const {
  if (at == nullptr) throw EsiError(fmt::format("{}: {}", file_, what));
  throw EsiError(fmt::format("{}:{}: <{}>: {}", file_, at->GetLineNum(), at->Name(), what));
}

std::string XmlReading::text(const tinyxml2::XMLElement* e) {
  const char* t = e != nullptr ? e->GetText() : nullptr;
  if (t == nullptr) return {};
  std::string_view s(t);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

const tinyxml2::XMLElement* XmlReading::child(const tinyxml2::XMLElement* parent, const char* name) {
  return parent != nullptr ? parent->FirstChildElement(name) : nullptr;
}

const tinyxml2::XMLElement* XmlReading::required(const tinyxml2::XMLElement* parent, const char* name) const {
  const tinyxml2::XMLElement* e = child(parent, name);
  if (e == nullptr) fail(parent, fmt::format("no <{}>", name));
  return e;
}

std::string XmlReading::english(const tinyxml2::XMLElement* parent, const char* name) {
  const tinyxml2::XMLElement* first = child(parent, name);
  for (const tinyxml2::XMLElement* e = first; e != nullptr; e = e->NextSiblingElement(name)) {
    const char* lcid = e->Attribute("LcId");
    if (lcid == nullptr || std::strcmp(lcid, "1033") == 0) return text(e);
  }
  return text(first);
}

std::optional<std::int64_t> XmlReading::parse_hexdec(std::string_view s) {
  std::int64_t value = 0;
  if (s.size() > 2 && s[0] == '#' && (s[1] == 'x' || s[1] == 'X')) {
    std::uint64_t u = 0;
    const auto [end, ec] = std::from_chars(s.data() + 2, s.data() + s.size(), u, 16);
    if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    return static_cast<std::int64_t>(u);  // a 64-bit pattern (ULINT limits) keeps its bits
  }
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value, 10);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return value;
}

std::int64_t XmlReading::number(const tinyxml2::XMLElement* e, std::int64_t lo, std::int64_t hi,
                                const char* attribute) const {
  const char* raw = attribute != nullptr ? e->Attribute(attribute) : nullptr;
  std::string t = attribute != nullptr ? (raw != nullptr ? std::string(raw) : std::string()) : text(e);
  const std::string what = attribute != nullptr ? std::string(attribute) : std::string("value");
  if (attribute != nullptr) {
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.back()))) t.pop_back();
    while (!t.empty() && std::isspace(static_cast<unsigned char>(t.front()))) t.erase(0, 1);
  }
  const std::optional<std::int64_t> v = parse_hexdec(t);
  if (!v) fail(e, fmt::format("{} '{}' is not a number (decimal, or hex as #x1A)", what, t));
  if (*v < lo || *v > hi) fail(e, fmt::format("{} {} is outside {}..{}", what, t, lo, hi));
  return *v;
}

std::optional<std::int64_t> XmlReading::optional_number(const tinyxml2::XMLElement* parent, const char* name,
                                                        std::int64_t lo, std::int64_t hi) const {
  const tinyxml2::XMLElement* e = child(parent, name);
  if (e == nullptr) return std::nullopt;
  return number(e, lo, hi);
}

std::optional<std::int64_t> XmlReading::optional_attribute(const tinyxml2::XMLElement* e, const char* attribute,
                                                           std::int64_t lo, std::int64_t hi) const {
  if (e == nullptr || e->Attribute(attribute) == nullptr) return std::nullopt;
  return number(e, lo, hi, attribute);
}

bool XmlReading::flag(const tinyxml2::XMLElement* e, const char* attribute, bool otherwise) const {
  const char* v = e != nullptr ? e->Attribute(attribute) : nullptr;
  if (v == nullptr) return otherwise;
  const std::string_view s(v);
  if (s == "true" || s == "1") return true;
  if (s == "false" || s == "0") return false;
  fail(e, fmt::format("{} '{}' is not a boolean (true, false, 1 or 0)", attribute, s));
}

std::vector<std::uint8_t> XmlReading::hex_binary(const tinyxml2::XMLElement* e) const {
  std::string digits;
  for (const char c : text(e))
    if (!std::isspace(static_cast<unsigned char>(c))) digits += c;
  if (digits.size() % 2 != 0) fail(e, "hexBinary with an odd number of digits");
  std::vector<std::uint8_t> out(digits.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto [end, ec] = std::from_chars(digits.data() + 2 * i, digits.data() + 2 * i + 2, out[i], 16);
    if (ec != std::errc() || end != digits.data() + 2 * i + 2)
      fail(e, fmt::format("'{}' is not hexBinary", digits.substr(2 * i, 2)));
  }
  return out;
}

}  // namespace vdrive::esi
