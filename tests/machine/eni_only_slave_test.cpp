// Slaves served from the ENI alone (tests/products/networks/eni_only.xml: a CoE module and a
// simple input terminal no ESI file describes): the device vdrive builds from what the ENI says of
// it (identity, mailbox, SyncManagers, the ENI's own PDO mapping, DC activation, the objects its
// CoE init commands write), the warning that says so, the network file that names it, and the
// refusal when the ENI says too little.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "vdrive/esi/eni_slave_device.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/machine/eni_reader.hpp"
#include "vdrive/profile/profile_loader.hpp"

namespace {

using namespace vdrive;

const std::string kEni = std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/networks/eni_only.xml";

bool any_contains(const std::vector<std::string>& lines, const std::string& what) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(what) != std::string::npos; });
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

// An ENI of one slave (vendor 1, product 2) with `slave_body` after its <Info>.
std::string one_slave(const std::string& slave_body) {
  return "<EtherCATConfig><Config>\n<Slave><Info><Name>Lonely</Name><PhysAddr>1001</PhysAddr><VendorId>1</VendorId>"
         "<ProductCode>2</ProductCode><RevisionNo>3</RevisionNo></Info>\n" + slave_body + "</Slave></Config></EtherCATConfig>\n";
}

// The device vdrive builds from the first <Slave> of `eni`.
esi::EniSlaveDevice device_of(const std::string& eni) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.Parse(eni.c_str()), tinyxml2::XML_SUCCESS);
  const esi::XmlReading xml("inline.xml");
  return esi::eni_slave_device(esi::read_eni_slave(xml, doc.RootElement()->FirstChildElement("Config")->FirstChildElement("Slave")));
}

TEST(EniOnly, ASlaveNothingMatchesIsServedFromTheEniWithAWarning) {
  const machine::EniNetwork n = machine::read_eni(kEni, {});
  ASSERT_EQ(n.network.slaves.size(), 2u);
  EXPECT_TRUE(n.network.slaves[0].device.ends_with("eni_only.xml#1001")) << n.network.slaves[0].device;
  EXPECT_TRUE(n.network.slaves[1].device.ends_with("eni_only.xml#1002")) << n.network.slaves[1].device;
  EXPECT_TRUE(any_contains(n.warnings, "slave 1 'Box 1 (XIO-4)' (vendor 0x0000ABCD, product 0x00001234, revision "
                                       "0x00010000): served from the ENI alone"))
      << joined(n.warnings);
  EXPECT_TRUE(any_contains(n.warnings, "no ESI for vendor 0x0000ABCD product 0x00001234 (searched no --esi-dir); assumed: "))
      << joined(n.warnings);
  EXPECT_TRUE(any_contains(n.warnings, "assumed: its TxPdo PDOs assigned to the one Inputs SyncManager")) << joined(n.warnings);
  // Every warning is a note too (the network file's comments).
  for (const std::string& w : n.warnings) EXPECT_TRUE(any_contains(n.notes, w)) << w;
}

TEST(EniOnly, TheDeviceHasTheEnisIdentitySyncManagersAndPdoMapping) {
  const machine::EniNetwork n = machine::read_eni(kEni, {});
  const auto box = esi::load_esi_device(n.network.slaves[0].device);
  EXPECT_EQ(box->profile.identity.vendor_id, 0xABCDu);
  EXPECT_EQ(box->profile.identity.product_code, 0x1234u);
  EXPECT_EQ(box->profile.identity.revision, 0x00010000u);
  EXPECT_EQ(box->profile.identity.device_name, "Box 1 (XIO-4)");
  ASSERT_EQ(box->profile.sync_managers.size(), 4u);
  EXPECT_EQ(box->profile.mailbox.rx_offset, 0x1000);
  EXPECT_EQ(box->profile.mailbox.rx_size, 128);
  EXPECT_EQ(box->profile.mailbox.tx_offset, 0x1080);
  EXPECT_EQ(box->profile.sync_managers[0].control, 0x26);  // from the init command that sets SM0 up
  EXPECT_EQ(box->profile.sync_managers[2].start, 0x1100);
  EXPECT_EQ(box->profile.sync_managers[2].length, 4);      // the PDOs assigned to it: 2 x 16 bits
  EXPECT_EQ(box->profile.sync_managers[2].control, 0x64);
  EXPECT_EQ(box->profile.sync_managers[3].start, 0x1180);
  EXPECT_EQ(box->profile.sync_managers[3].length, 6);
  ASSERT_EQ(box->profile.rx_pdos.size(), 1u);
  EXPECT_EQ(box->profile.rx_pdos[0].index, 0x1601);        // the ENI's mapping, not a default 1600h
  EXPECT_EQ(box->profile.rx_pdos[0].sync_manager, 2);
  ASSERT_EQ(box->profile.tx_pdos.size(), 1u);
  EXPECT_TRUE(box->profile.tx_pdos[0].fixed);
  EXPECT_NE(box->profile.mailbox.protocols & 0x0004, 0) << "CoE";
  // DC activation 0981h = 03h from the register init command.
  const std::vector<std::uint8_t>& dc = box->profile.sync.accepted_dc_activation;
  EXPECT_NE(std::find(dc.begin(), dc.end(), 0x03), dc.end());
  EXPECT_EQ(std::find(dc.begin(), dc.end(), 0x07), dc.end());
  // The objects behind its PDOs and the assignment as the ENI makes it.
  const od::EntryDesc* assign = box->dictionary->find(0x1C12, 1);
  ASSERT_NE(assign, nullptr);
  EXPECT_EQ(assign->default_value, (std::vector<std::uint8_t>{0x01, 0x16}));
  EXPECT_NE(assign->access & od::access::kWritePreOp, 0) << "the ENI writes 1C12h: PDO assignment";
  ASSERT_NE(box->dictionary->find(0x7000, 2), nullptr);
  EXPECT_NE(box->dictionary->find(0x7000, 2)->access & od::access::kRxPdoMappable, 0);
  ASSERT_NE(box->dictionary->find(0x6000, 3), nullptr);
}

TEST(EniOnly, ObjectsItsCoeInitCommandsWriteAreCreated) {
  const machine::EniNetwork n = machine::read_eni(kEni, {});
  const auto box = esi::load_esi_device(n.network.slaves[0].device);
  const od::EntryDesc* filter = box->dictionary->find(0x8000, 1);
  const od::EntryDesc* scaling = box->dictionary->find(0x8000, 2);
  ASSERT_NE(filter, nullptr);
  ASSERT_NE(scaling, nullptr);
  EXPECT_EQ(filter->type, od::DataType::Unsigned16);
  EXPECT_EQ(scaling->type, od::DataType::Unsigned32);
  EXPECT_EQ(filter->name, "Filter time");
  EXPECT_NE(filter->access & od::access::kWritePreOp, 0);
  EXPECT_EQ(filter->access & od::access::kWriteOp, 0);
  ASSERT_NE(box->dictionary->find(0x8000, 0), nullptr);
  EXPECT_EQ(box->dictionary->find(0x8000, 0)->default_value, (std::vector<std::uint8_t>{2}));
  EXPECT_TRUE(any_contains(n.warnings, "8000h:01h created for its CoE init command (line 45): U16, readable, writable in Pre-Op"))
      << joined(n.warnings);
  // Created for the start-up to succeed: none of the ENI's own commands is refused.
  EXPECT_FALSE(any_contains(n.warnings, "the device answers abort")) << joined(n.warnings);
}

TEST(EniOnly, ASimpleIoSlaveTakesItsSyncManagerFromTheRegisterInitCommands) {
  const machine::EniNetwork n = machine::read_eni(kEni, {});
  const auto term = esi::load_esi_device(n.network.slaves[1].device);
  EXPECT_FALSE(term->profile.has_mailbox());
  ASSERT_EQ(term->profile.sync_managers.size(), 1u);
  EXPECT_EQ(term->profile.sync_managers[0].start, 0x1000);
  EXPECT_EQ(term->profile.sync_managers[0].length, 1);
  ASSERT_EQ(term->profile.tx_pdos.size(), 1u);
  EXPECT_EQ(term->profile.tx_pdos[0].sync_manager, 0);
  ASSERT_NE(term->dictionary->find(0x6000, 1), nullptr);
}

TEST(EniOnly, TheNetworkFileItWritesNamesTheEniSlaveAndLoadsBack) {
  const machine::EniNetwork n = machine::read_eni(kEni, {});
  const std::string yaml = machine::to_network_yaml(n.network, n.notes);
  EXPECT_NE(yaml.find("# slave 1 'Box 1 (XIO-4)'"), std::string::npos) << yaml;
  const machine::NetworkFile f = machine::parse_network_file(yaml, "from-eni.yaml", ".");
  ASSERT_EQ(f.slaves.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(f.slaves[i].name, n.network.slaves[i].name);
    EXPECT_EQ(f.slaves[i].device, n.network.slaves[i].device);
  }
  EXPECT_EQ(esi::load_esi_device(f.slaves[1].device)->profile.identity.product_code, 0x5678u);
}

TEST(EniOnly, TheBootStrapMailboxIsTheDevicesBootMailbox) {
  const esi::EniSlaveDevice d = device_of(one_slave(
      "<Mailbox><Send><Start>16384</Start><Length>276</Length></Send><Recv><Start>18432</Start><Length>276</Length></Recv>"
      "<BootStrap><Send><Start>16384</Start><Length>1024</Length></Send><Recv><Start>18432</Start><Length>1024</Length></Recv>"
      "</BootStrap><Protocol>CoE</Protocol><Protocol>FoE</Protocol></Mailbox>\n"));
  EXPECT_EQ(d.device.boot_strap, (std::vector<std::uint8_t>{0x00, 0x40, 0x00, 0x04, 0x00, 0x48, 0x00, 0x04}));
  EXPECT_TRUE(d.device.coe);
  EXPECT_TRUE(d.device.foe);
  const esi::ImportedDevice imported = esi::import_device(d.device);
  EXPECT_TRUE(imported.profile.has_bootstrap);
  EXPECT_EQ(imported.profile.mailbox.boot_rx_size, 1024);
}

TEST(EniOnly, WithoutAMailboxTheEnisSm2IsTheSm0ItsInitCommandsSetUp) {
  // As configurators describe a digital output terminal: the output SM as <Sm2>, without an
  // address, and the register init command that sets the device's SM0 up.
  const esi::EniSlaveDevice d = device_of(one_slave(
      "<ProcessData><Send><BitLength>8</BitLength></Send><Sm2><Type>Outputs</Type><Enable>1</Enable></Sm2>"
      "<RxPdo Sm=\"2\"><Index>#x1600</Index><Entry><Index>#x7000</Index><SubIndex>1</SubIndex><BitLen>8</BitLen></Entry></RxPdo>"
      "</ProcessData>\n<InitCmds><InitCmd><Transition>PS</Transition><Cmd>5</Cmd><Ado>2048</Ado><Data>0011010044000100</Data>"
      "</InitCmd></InitCmds>\n"));
  ASSERT_EQ(d.device.sync_managers.size(), 1u);
  EXPECT_EQ(d.device.sync_managers[0].kind, "Outputs");
  EXPECT_EQ(d.device.sync_managers[0].start, 0x1100);
  EXPECT_EQ(d.device.sync_managers[0].control, 0x44);
  EXPECT_EQ(d.device.sync_managers[0].default_size, 1);
  ASSERT_EQ(d.device.rx_pdos.size(), 1u);
  EXPECT_EQ(d.device.rx_pdos[0].sm, 0);
  EXPECT_NE(std::find_if(d.assumptions.begin(), d.assumptions.end(),
                         [](const std::string& a) { return a.find("SM2 of the ENI is the device's SM0") != std::string::npos; }),
            d.assumptions.end());
}

TEST(EniOnly, ProcessDataWithoutASyncManagerAddressIsRefused) {
  const std::string eni = one_slave(
      "<ProcessData><Send><BitLength>8</BitLength></Send>\n"
      "<Sm2><Type>Outputs</Type><ControlByte>100</ControlByte><Enable>1</Enable></Sm2>\n"
      "<RxPdo Sm=\"2\"><Index>#x1600</Index><Entry><Index>#x7000</Index><SubIndex>1</SubIndex><BitLen>8</BitLen></Entry></RxPdo>"
      "</ProcessData>\n<Mailbox><Send><Start>4096</Start><Length>64</Length></Send><Recv><Start>4160</Start><Length>64</Length></Recv></Mailbox>\n");
  try {
    machine::parse_eni(eni, "lonely.xml", {});
    FAIL() << "an output SM without an address";
  } catch (const machine::NetworkFileError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("lonely.xml:4: <Sm2>: slave 'Lonely' (vendor 0x00000001, product 0x00000002, revision 0x00000003): "
                     "Outputs without a <StartAddress>, and no init command sets SM2 up"), std::string::npos) << m;
    EXPECT_NE(m.find("cannot be served from the ENI alone"), std::string::npos) << m;
    EXPECT_NE(m.find("no built-in product and no ESI device matches it (searched no --esi-dir)"), std::string::npos) << m;
  }
}

TEST(EniOnly, InputsWithoutAnySyncManagerAreRefused) {
  const std::string eni = one_slave("<ProcessData><Recv><BitLength>16</BitLength></Recv></ProcessData>\n");
  try {
    machine::parse_eni(eni, "lonely.xml", {});
    FAIL() << "inputs without any SM";
  } catch (const machine::NetworkFileError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("lonely.xml:3: <ProcessData>: slave 'Lonely'"), std::string::npos) << m;
    EXPECT_NE(m.find("16 bits of inputs but no <SmN> of Type Inputs with a <StartAddress>"), std::string::npos) << m;
  }
}

TEST(EniOnly, APdoOnASyncManagerTheEniDoesNotSetUpIsRefused) {
  const std::string eni = one_slave(
      "<ProcessData><Sm3><Type>Inputs</Type><StartAddress>4352</StartAddress></Sm3>\n"
      "<TxPdo Sm=\"2\"><Index>#x1a00</Index><Entry><Index>#x6000</Index><SubIndex>1</SubIndex><BitLen>8</BitLen></Entry></TxPdo>"
      "</ProcessData>\n<Mailbox><Send><Start>4096</Start><Length>64</Length></Send><Recv><Start>4160</Start><Length>64</Length></Recv></Mailbox>\n");
  try {
    machine::parse_eni(eni, "lonely.xml", {});
    FAIL();
  } catch (const machine::NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("lonely.xml:4: <TxPdo>: slave 'Lonely'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("PDO 1A00h is assigned to SM2, which the ENI does not set up"), std::string::npos)
        << e.what();
  }
}

TEST(EniOnly, WithoutAPhysAddrItCannotBeNamed) {
  const std::string eni = "<EtherCATConfig><Config><Slave><Info><Name>Anon</Name><VendorId>1</VendorId><ProductCode>2"
                          "</ProductCode></Info></Slave></Config></EtherCATConfig>";
  try {
    machine::parse_eni(eni, "anon.xml", {});
    FAIL();
  } catch (const machine::NetworkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("anon.xml:1: <Slave>: slave 1 'Anon'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("without a <PhysAddr>"), std::string::npos) << e.what();
  }
}

TEST(EniOnly, AReferenceToASlaveTheEniDoesNotHaveIsAnError) {
  EXPECT_THROW(esi::load_esi_device(kEni + "#4711"), profile::ProfileError);
  EXPECT_THROW(esi::load_esi_device(kEni + "#x"), profile::ProfileError);
}

}  // namespace
