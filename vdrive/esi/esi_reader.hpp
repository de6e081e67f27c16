#pragma once
// Reads an EtherCAT Slave Information file (EtherCATInfo XML, ETG.2000) with tinyxml2: every
// <Device> of it, as EsiDevice (esi_device.hpp). What it needs and does not find, or cannot read,
// is an EsiError naming the file, the line and the element.
#include <string>
#include <string_view>
#include <vector>

#include "vdrive/esi/esi_device.hpp"
#include "vdrive/esi/xml_reading.hpp"

namespace vdrive::esi {

std::vector<EsiDevice> read_esi_file(const std::string& path);
// The same for a document in memory; `file` names it in messages.
std::vector<EsiDevice> parse_esi(std::string_view xml, const std::string& file);

// One <RxPdo>/<TxPdo> (ETG.2000 PdoType; an ENI's <ProcessData> uses the same type).
EsiPdo read_pdo(const XmlReading& xml, const tinyxml2::XMLElement* pdo);

}  // namespace vdrive::esi
