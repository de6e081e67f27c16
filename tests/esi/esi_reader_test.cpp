// Reading ESI files: the hand-written generic servo (tests/products/esi/generic_servo.xml) comes in
// with its ETG arrays, access restrictions, HexDec values, PDO rules and DC op modes; broken files
// and ambiguous device names get errors naming the file, the line and the element.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vdrive/esi/esi_error.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/esi/esi_reader.hpp"

namespace {

using namespace vdrive;

const std::string kServo = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi/generic_servo.xml";

// The message of the EsiError `f` throws ("" when it throws none).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const esi::EsiError& e) {
    return e.what();
  }
  return {};
}

std::string device_xml(const std::string& body, const std::string& type = R"(<Type ProductCode="#x1" RevisionNo="#x2">T1</Type>)") {
  return "<?xml version=\"1.0\"?>\n<EtherCATInfo>\n<Vendor><Id>#x99</Id><Name>V</Name></Vendor>\n<Descriptions>\n"
         "<Devices>\n<Device Physics=\"YY\">\n" + type + "\n<Name>N</Name>\n" + body +
         "\n</Device>\n</Devices>\n</Descriptions>\n</EtherCATInfo>\n";
}

TEST(EsiReader, ReadsTheGenericServo) {
  const std::vector<esi::EsiDevice> devices = esi::read_esi_file(kServo);
  ASSERT_EQ(devices.size(), 1u);
  const esi::EsiDevice& d = devices[0];
  EXPECT_EQ(d.vendor_id, 0x00FFFF01u);
  EXPECT_EQ(d.product_code, 0x402u);
  EXPECT_EQ(d.type_text, "GS402");
  EXPECT_EQ(d.name, "Generic Servo 402");
  EXPECT_EQ(d.profile_no, 402u);
  ASSERT_EQ(d.sync_managers.size(), 4u);
  EXPECT_EQ(d.sync_managers[2].start, 0x1100);
  EXPECT_EQ(d.sync_managers[2].control, 0x64);
  ASSERT_EQ(d.rx_pdos.size(), 2u);
  EXPECT_EQ(d.rx_pdos[0].exclude, std::vector<std::uint16_t>{0x1601});
  EXPECT_TRUE(d.rx_pdos[1].fixed);
  EXPECT_FALSE(d.rx_pdos[1].sm.has_value());
  EXPECT_TRUE(d.tx_pdos[0].mandatory);
  ASSERT_EQ(d.op_modes.size(), 2u);
  EXPECT_EQ(d.op_modes[1].assign_activate, 0x0300);
  EXPECT_EQ(d.op_modes[1].cycle_time_sync0_factor, 1);
}

TEST(EsiReader, EtgArraysExpandIntoTheirElements) {
  const esi::EsiDevice d = esi::read_esi_file(kServo).at(0);
  const auto it = std::find_if(d.objects.begin(), d.objects.end(), [](const od::ObjectDesc& o) { return o.index == 0x1C12; });
  ASSERT_NE(it, d.objects.end());
  EXPECT_EQ(it->code, od::ObjectCode::Array);
  ASSERT_EQ(it->entries.size(), 3u);
  EXPECT_EQ(it->entries[2].subindex, 2);
  EXPECT_EQ(it->entries[2].type, od::DataType::Unsigned16);
  EXPECT_EQ(it->entries[1].default_value, (std::vector<std::uint8_t>{0x00, 0x16}));
  // rw with WriteRestrictions="PreOP": readable always, writable in PreOp only.
  EXPECT_EQ(it->entries[1].access, od::access::kReadAll | od::access::kWritePreOp);
}

TEST(EsiReader, ValuesComeFromDataAndHexDecForms) {
  const esi::EsiDevice d = esi::read_esi_file(kServo).at(0);
  auto entry = [&](std::uint16_t index, std::uint8_t sub) -> const od::EntryDesc& {
    for (const od::ObjectDesc& o : d.objects)
      if (o.index == index)
        if (const od::EntryDesc* e = o.entry(sub)) return *e;
    throw std::runtime_error("no entry");
  };
  EXPECT_EQ(entry(0x6080, 0).min, 0);
  EXPECT_EQ(entry(0x6080, 0).max, 10000);
  EXPECT_EQ(entry(0x6080, 0).default_value, (std::vector<std::uint8_t>{0x70, 0x17, 0, 0}));  // 6000
  EXPECT_EQ(entry(0x1C32, 5).default_value, (std::vector<std::uint8_t>{0x48, 0xE8, 0x01, 0}));  // #x0001E848
  EXPECT_EQ(entry(0x6098, 0).min, 1);
  EXPECT_EQ(entry(0x1008, 0).type, od::DataType::VisibleString);
  EXPECT_EQ(entry(0x6041, 0).access, od::access::kReadAll | od::access::kTxPdoMappable);
  EXPECT_EQ(entry(0x1C32, 0x20).type, od::DataType::Boolean);
}

TEST(EsiReader, ImportMakesTheProfileFromTheFile) {
  const esi::ImportedDevice imported = esi::import_device(esi::read_esi_file(kServo).at(0));
  const profile::ProductProfile& p = imported.profile;
  EXPECT_EQ(p.esc.port_descriptor, 0x0F);
  EXPECT_EQ(p.esc.pdi_control, 0x0C05);
  EXPECT_EQ(p.mailbox_rules.sm0_min_length, 34);
  EXPECT_EQ(p.mailbox_rules.sm0_max_length, 128);
  EXPECT_EQ(p.coe_details, 0x2F);  // SDO, SDO info, PDO assign, PDO config, complete access
  EXPECT_TRUE(p.sync.dc_sync0);
  EXPECT_FALSE(p.sync.dc_sync1);
  EXPECT_EQ(p.sync.accepted_dc_activation, (std::vector<std::uint8_t>{0x00, 0x03}));
  EXPECT_EQ(p.sync.cycle_min_ns, 125000u);
  EXPECT_TRUE(p.sync.accepts_cycle(1'000'000));
  EXPECT_FALSE(p.sync.accepts_cycle(100'000));
  ASSERT_EQ(p.rx_pdos.size(), 1u);
  EXPECT_EQ(p.rx_pdos[0].index, 0x1600);
  ASSERT_EQ(p.pdo_rules.rx_objects.size(), 2u);
  EXPECT_EQ(p.pdo_rules.rx_objects[0].max_entries, 8);
  EXPECT_EQ(p.pdo_rules.rx_objects[0].excludes, std::vector<std::uint16_t>{0x1601});
  EXPECT_TRUE(p.pdo_rules.tx_objects[0].mandatory);
  EXPECT_EQ(p.pdo_rules.max_rx_assigned, 2);
  EXPECT_EQ(p.modes.supported_drive_modes, 0x3A5u);
  EXPECT_EQ(p.modes.default_mode, 8);
  EXPECT_EQ(p.homing.default_method, 35);
  EXPECT_EQ(imported.sii_image.size(), 2048u);
  EXPECT_EQ(imported.dictionary->find(0x1018, 2)->default_value, (std::vector<std::uint8_t>{0x02, 0x04, 0, 0}));
}

TEST(EsiReader, MalformedXmlNamesTheLine) {
  const std::string e = error_of([] { esi::parse_esi("<?xml version=\"1.0\"?>\n<EtherCATInfo>\n<Vendor>\n</EtherCATInfo>", "bad.xml"); });
  EXPECT_NE(e.find("bad.xml:"), std::string::npos) << e;
  EXPECT_NE(e.find("not well-formed"), std::string::npos) << e;
}

TEST(EsiReader, ANonEsiDocumentIsRefused) {
  const std::string e = error_of([] { esi::parse_esi("<EtherCATConfig/>", "eni.xml"); });
  EXPECT_NE(e.find("eni.xml:1: <EtherCATConfig>: not an ESI file"), std::string::npos) << e;
}

TEST(EsiReader, ABadNumberNamesLineElementAndText) {
  const std::string xml = device_xml(R"(<Sm StartAddress="#xZZ" ControlByte="#x26" Enable="1">MBoxOut</Sm>)");
  const std::string e = error_of([&] { esi::parse_esi(xml, "d.xml"); });
  EXPECT_NE(e.find("d.xml:9: <Sm>: StartAddress '#xZZ' is not a number"), std::string::npos) << e;
}

TEST(EsiReader, AnUnknownSyncManagerKindIsNamed) {
  const std::string e = error_of([&] { esi::parse_esi(device_xml("<Sm StartAddress=\"#x1000\">Mailbox</Sm>"), "d.xml"); });
  EXPECT_NE(e.find("d.xml:9: <Sm>: 'Mailbox': expected MBoxOut, MBoxIn, Outputs or Inputs"), std::string::npos) << e;
}

TEST(EsiReader, AnUnknownObjectTypeIsNamed) {
  const std::string xml = device_xml(
      "<GroupType>G</GroupType>\n<Profile><Dictionary><Objects>\n"
      "<Object><Index>#x2000</Index><Name>X</Name><Type>WIDGET</Type><BitSize>8</BitSize></Object>\n"
      "</Objects></Dictionary></Profile>");
  const std::string e = error_of([&] { esi::parse_esi(xml, "d.xml"); });
  EXPECT_NE(e.find("d.xml:11: <Object>: object 2000h sub 0: type 'WIDGET'"), std::string::npos) << e;
}

TEST(EsiReader, ABadAccessIsNamed) {
  const std::string xml = device_xml(
      "<GroupType>G</GroupType>\n<Profile><Dictionary><Objects>\n"
      "<Object><Index>#x2000</Index><Name>X</Name><Type>UINT</Type><BitSize>16</BitSize>\n"
      "<Flags><Access>read</Access></Flags></Object>\n</Objects></Dictionary></Profile>");
  const std::string e = error_of([&] { esi::parse_esi(xml, "d.xml"); });
  EXPECT_NE(e.find("d.xml:12: <Access>: 'read': expected ro, rw or wo"), std::string::npos) << e;
}

TEST(EsiReader, DeviceReferencesNameProductAndRevision) {
  EXPECT_TRUE(esi::is_esi_reference("a/b/Devices.XML"));
  EXPECT_TRUE(esi::is_esi_reference("d.xml:0x10:2"));
  EXPECT_FALSE(esi::is_esi_reference("a6b"));
  const esi::DeviceReference r = esi::parse_device_reference("dir/d.xml:0x3F03052:#x00110000");
  EXPECT_EQ(r.path, "dir/d.xml");
  EXPECT_EQ(r.product_code, 0x3F03052u);
  EXPECT_EQ(r.revision, 0x00110000u);
  EXPECT_FALSE(esi::parse_device_reference("d.xml").product_code.has_value());
  const std::string e = error_of([] { esi::parse_device_reference("d.xml:12ab"); });
  EXPECT_NE(e.find("the product code '12ab' is not a number"), std::string::npos) << e;
}

TEST(EsiReader, SeveralDevicesNeedAProductCode) {
  std::string xml = device_xml("<GroupType>G</GroupType>");
  const std::string second = "<Device><Type ProductCode=\"#x5\" RevisionNo=\"#x1\">T5</Type><Name>N5</Name><GroupType>G</GroupType></Device>\n";
  xml.insert(xml.find("</Devices>"), second);
  const std::vector<esi::EsiDevice> devices = esi::parse_esi(xml, "two.xml");
  ASSERT_EQ(devices.size(), 2u);
  const std::string e = error_of([&] { esi::select_device(devices, esi::parse_device_reference("two.xml")); });
  EXPECT_NE(e.find("2 devices match"), std::string::npos) << e;
  EXPECT_NE(e.find("two.xml:0x00000005:0x00000001"), std::string::npos) << e;
  EXPECT_EQ(esi::select_device(devices, esi::parse_device_reference("two.xml:5")).type_text, "T5");
  const std::string none = error_of([&] { esi::select_device(devices, esi::parse_device_reference("two.xml:7")); });
  EXPECT_NE(none.find("no device with product code 0x00000007"), std::string::npos) << none;
}

TEST(EsiReader, AMissingFileIsNamed) {
  const std::string e = error_of([] { esi::load_esi_device("/nonexistent/dir/x.xml"); });
  EXPECT_NE(e.find("/nonexistent/dir/x.xml: cannot read the ESI file"), std::string::npos) << e;
}

}  // namespace

namespace {

// SII categories (type, words) from word 40h on.
std::vector<std::pair<std::uint16_t, std::uint16_t>> categories(const std::vector<std::uint8_t>& sii) {
  std::vector<std::pair<std::uint16_t, std::uint16_t>> out;
  for (std::size_t at = 0x80; at + 4 <= sii.size();) {
    const auto type = static_cast<std::uint16_t>(sii[at] | sii[at + 1] << 8);
    if (type == 0xFFFF) break;
    const auto words = static_cast<std::uint16_t>(sii[at + 2] | sii[at + 3] << 8);
    out.emplace_back(type, words);
    at += 4 + 2u * words;
  }
  return out;
}

// SOEM and IgH read every PDO of the first TxPDO/RxPDO category: all eight channel PDOs of an input
// terminal are in one category (8 bytes of PDO header and 8 of entry each: 64 words).
TEST(EsiSii, AllPdosOfADirectionAreInOneCategory) {
  const std::string io = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi/io_terminals.xml";
  const esi::ImportedDevice d = esi::import_device(esi::select_device(esi::read_esi_file(io), esi::parse_device_reference(io + ":0x03f03052")));
  std::size_t tx = 0;
  for (const auto& [type, words] : categories(d.sii_image)) {
    if (type != 50) continue;
    ++tx;
    EXPECT_EQ(words, 8 * 16 / 2);
  }
  EXPECT_EQ(tx, 1u);
}

}  // namespace

namespace {

using namespace vdrive;

std::string device(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<EtherCATInfo>\n<Vendor><Id>#x99</Id><Name>V</Name></Vendor>\n<Descriptions>\n"
         "<Devices>\n<Device Physics=\"YY\">\n<Type ProductCode=\"#x1\" RevisionNo=\"#x2\">T1</Type>\n<Name>N</Name>\n"
         "<GroupType>G</GroupType>\n" + body + "\n</Device>\n</Devices>\n</Descriptions>\n</EtherCATInfo>\n";
}

std::string import_error(const std::string& xml) {
  try {
    esi::import_device(esi::parse_esi(xml, "d.xml").at(0));
  } catch (const esi::EsiError& e) {
    return e.what();
  }
  return {};
}

// Vendors' files: a record SubItem of type "ARRAY [0..7] OF BYTE" with its own SubIdx is one
// 8-byte entry, not eight subindexes.
TEST(EsiVendorFiles, AByteArraySubItemIsOneOctetString) {
  const std::string xml = device(
      "<Profile><Dictionary><DataTypes>\n"
      "<DataType><Name>USINT</Name><BitSize>8</BitSize></DataType>\n"
      "<DataType><Name>ARRAY [0..7] OF BYTE</Name><BaseType>BYTE</BaseType><BitSize>64</BitSize>"
      "<ArrayInfo><LBound>0</LBound><Elements>8</Elements></ArrayInfo></DataType>\n"
      "<DataType><Name>DT2000</Name><BitSize>80</BitSize>"
      "<SubItem><SubIdx>0</SubIdx><Name>SubIndex 000</Name><Type>USINT</Type><BitSize>8</BitSize><BitOffs>0</BitOffs></SubItem>"
      "<SubItem><SubIdx>1</SubIdx><Name>Blob</Name><Type>ARRAY [0..7] OF BYTE</Type><BitSize>64</BitSize><BitOffs>16</BitOffs></SubItem>"
      "</DataType>\n</DataTypes><Objects>\n"
      "<Object><Index>#x2000</Index><Name>Blob record</Name><Type>DT2000</Type><BitSize>80</BitSize><Flags><Access>ro</Access></Flags></Object>\n"
      "</Objects></Dictionary></Profile>");
  const esi::EsiDevice d = esi::parse_esi(xml, "d.xml").at(0);
  ASSERT_EQ(d.objects.size(), 1u);
  ASSERT_EQ(d.objects[0].entries.size(), 2u);
  EXPECT_EQ(d.objects[0].entries[1].type, od::DataType::OctetString);
  EXPECT_EQ(d.objects[0].entries[1].bit_length, 64);
}

// IgH's `ethercat xml` writes <Sm> without a type: it follows from the control byte.
TEST(EsiVendorFiles, ASyncManagerWithoutTextTakesItsKindFromTheControlByte) {
  const std::string xml = device(
      "<Sm StartAddress=\"#x1000\" ControlByte=\"#x26\" Enable=\"1\"/>\n<Sm StartAddress=\"#x1080\" ControlByte=\"#x22\" Enable=\"1\"/>\n"
      "<Sm StartAddress=\"#x1100\" ControlByte=\"#x64\" Enable=\"1\"/>\n<Sm StartAddress=\"#x1180\" ControlByte=\"#x20\" Enable=\"1\"/>");
  const esi::EsiDevice d = esi::parse_esi(xml, "d.xml").at(0);
  ASSERT_EQ(d.sync_managers.size(), 4u);
  EXPECT_EQ(d.sync_managers[0].kind, "MBoxOut");
  EXPECT_EQ(d.sync_managers[1].kind, "MBoxIn");
  EXPECT_EQ(d.sync_managers[2].kind, "Outputs");
  EXPECT_EQ(d.sync_managers[3].kind, "Inputs");
}

// The file's own PDOs are what the device maps, even where the dictionary has no PdoMapping.
TEST(EsiVendorFiles, WhatTheFilesPdosMapIsMappable) {
  const std::string xml = device(
      "<Profile><Dictionary><DataTypes><DataType><Name>UINT</Name><BitSize>16</BitSize></DataType></DataTypes><Objects>\n"
      "<Object><Index>#x6041</Index><Name>Statusword</Name><Type>UINT</Type><BitSize>16</BitSize><Flags><Access>ro</Access></Flags></Object>\n"
      "</Objects></Dictionary></Profile>\n"
      "<Sm StartAddress=\"#x1180\" ControlByte=\"#x20\" Enable=\"1\">Inputs</Sm>\n"
      "<TxPdo Fixed=\"1\" Sm=\"0\"><Index>#x1A00</Index><Name>In</Name>"
      "<Entry><Index>#x6041</Index><SubIndex>0</SubIndex><BitLen>16</BitLen><Name>Statusword</Name><DataType>UINT</DataType></Entry></TxPdo>");
  const esi::ImportedDevice d = esi::import_device(esi::parse_esi(xml, "d.xml").at(0));
  EXPECT_EQ(d.dictionary->find(0x6041, 0)->access, od::access::kReadAll | od::access::kTxPdoMappable);
}

TEST(EsiVendorFiles, APdoMappingItsOwnMappingObjectIsRefused) {
  const std::string e = import_error(device(
      "<Sm StartAddress=\"#x1100\" ControlByte=\"#x64\" Enable=\"1\">Outputs</Sm>\n"
      "<RxPdo Fixed=\"1\" Sm=\"0\"><Index>#x1600</Index><Name>Out</Name>\n"
      "<Entry><Index>#x1600</Index><SubIndex>1</SubIndex><BitLen>32</BitLen><Name>x</Name><DataType>UDINT</DataType></Entry></RxPdo>"));
  EXPECT_NE(e.find("d.xml:12: <Entry>: PDO 1600h maps 1600h:01h, a PDO mapping or assignment object"), std::string::npos) << e;
}

// A digital output terminal's SM0 on the digital output data (0F00h) is served; anything else in
// the register area is refused with the reason.
TEST(EsiVendorFiles, ProcessDataInTheRegisterAreaIsRefusedWithTheReason) {
  const std::string inputs = import_error(device("<Sm StartAddress=\"#x0F00\" ControlByte=\"#x00\" Enable=\"1\">Inputs</Sm>"));
  EXPECT_NE(inputs.find("d.xml:10: <Sm>: Inputs at 0F00h, 0 bytes, in the ESC's register area"), std::string::npos) << inputs;
  const std::string wide =
      import_error(device("<Sm StartAddress=\"#x0F00\" DefaultSize=\"2\" ControlByte=\"#x44\" Enable=\"1\">Outputs</Sm>"));
  EXPECT_NE(wide.find("Outputs at 0F00h, 2 bytes, in the ESC's register area"), std::string::npos) << wide;
  EXPECT_EQ(import_error(device("<Sm StartAddress=\"#x0F00\" DefaultSize=\"1\" ControlByte=\"#x44\" Enable=\"1\">Outputs</Sm>")),
            "") << "a digital output terminal's SM0";
}

}  // namespace
