#pragma once
// Reading values out of an ESI document (tinyxml2): element text, ETG.2000 HexDecValue ("#x1A",
// "26", "-3") and hexBinary, children by name; every failure an EsiError naming file, line and
// element.
#include <tinyxml2.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/esi/esi_error.hpp"

namespace vdrive::esi {

class XmlReading {
public:
  explicit XmlReading(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  [[noreturn]] void fail(const tinyxml2::XMLElement* at, const std::string& what) const;

  // Trimmed text of `e` ("" for none).
  static std::string text(const tinyxml2::XMLElement* e);
  // The child `name` of `parent`, or nullptr / an error when it is required.
  static const tinyxml2::XMLElement* child(const tinyxml2::XMLElement* parent, const char* name);
  const tinyxml2::XMLElement* required(const tinyxml2::XMLElement* parent, const char* name) const;
  // Among the children `name`, the English one (LcId 1033), else the first; its text.
  static std::string english(const tinyxml2::XMLElement* parent, const char* name);

  // HexDecValue in [lo, hi], from the text of `e` or of its attribute `attribute`.
  std::int64_t number(const tinyxml2::XMLElement* e, std::int64_t lo, std::int64_t hi,
                      const char* attribute = nullptr) const;
  std::optional<std::int64_t> optional_number(const tinyxml2::XMLElement* parent, const char* name,
                                              std::int64_t lo, std::int64_t hi) const;
  std::optional<std::int64_t> optional_attribute(const tinyxml2::XMLElement* e, const char* attribute,
                                                 std::int64_t lo, std::int64_t hi) const;
  // xs:boolean attribute ("true", "1", "false", "0"); `otherwise` when absent.
  bool flag(const tinyxml2::XMLElement* e, const char* attribute, bool otherwise) const;
  // xs:hexBinary text of `e`.
  std::vector<std::uint8_t> hex_binary(const tinyxml2::XMLElement* e) const;

  // HexDecValue text; nullopt when it is not one.
  static std::optional<std::int64_t> parse_hexdec(std::string_view text);

private:
  std::string file_;
};

}  // namespace vdrive::esi
