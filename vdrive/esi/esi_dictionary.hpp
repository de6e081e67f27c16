#pragma once
// The <Dictionary> of an ESI device (ETG.2000 DictionaryType): <DataTypes> (the basic types used,
// plus one DTxxxx type per ARRAY/RECORD object, described by SubItems) and <Objects> (index, name,
// type, bit size, Info with MinData/MaxData/DefaultData, Flags with Access and PdoMapping).
#include "vdrive/esi/xml_writer.hpp"
#include "vdrive/od/dictionary.hpp"

namespace vdrive::esi {

void write_dictionary(XmlWriter& xml, const od::Dictionary& dictionary);

// ESI <Access> text ("ro", "rw", "wo"; "" = no documented access) and the ReadRestrictions /
// WriteRestrictions attribute values ("PreOP", "PreOP_SafeOP", ...; "" = all states).
struct AccessText {
  std::string access, read_restrictions, write_restrictions;
};
AccessText access_text(std::uint16_t access_bits);
// "R", "T", "RT" or "" from the PDO-mappable access bits.
std::string pdo_mapping_text(std::uint16_t access_bits);

}  // namespace vdrive::esi
