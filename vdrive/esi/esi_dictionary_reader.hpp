#pragma once
// The object dictionary of an ESI device (<Profile><Dictionary>, ETG.2000 DictionaryType) as the
// OD engine describes one: <DataTypes> resolve each object's type (basic types, records of
// SubItems, ETG arrays: a DTxxxx of "SubIndex 000" and an element array with ArrayInfo), <Objects>
// give names, access (Flags/Access with Read/WriteRestrictions, PdoMapping) and values
// (DefaultData/MinData/MaxData, DefaultValue/MinValue/MaxValue, DefaultString). See docs/esi.md.
#include <tinyxml2.h>

#include <optional>
#include <string_view>
#include <vector>

#include "vdrive/esi/xml_reading.hpp"
#include "vdrive/od/dictionary.hpp"

namespace vdrive::esi {

// Objects sorted by index, each entry's value_bytes and default_value set. Throws EsiError.
std::vector<od::ObjectDesc> read_dictionary(const XmlReading& xml, const tinyxml2::XMLElement* dictionary);

// An ETG.2000 basic type ("UINT", "BOOL", "BIT3", "STRING(16)", ...) of `bit_size` bits as the OD
// engine stores it; nullopt when the name is not a basic type it knows.
struct BasicType {
  od::DataType type;
  std::uint16_t bits;
};
std::optional<BasicType> basic_type(std::string_view name, std::uint32_t bit_size);

// The CoE data type code (0x0006 for UINT) of a PDO entry's DataType text; 0 when unknown.
std::uint8_t coe_code(std::string_view name);

}  // namespace vdrive::esi
