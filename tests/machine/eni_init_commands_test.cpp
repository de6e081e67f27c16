// The ENI's init commands tried on the device a slave is served as, answered as that device
// answers them: a CoE init command the device refuses is a warning naming the slave, the command's
// line, index:subindex and the abort code with its text; the start-up's own sequence (1C12h:00h =
// 0, the entries, the count) is taken; mailbox SyncManagers and a DC activation the device would
// refuse are warnings with the AL status code.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "vdrive/machine/eni_reader.hpp"

namespace {

using namespace vdrive;

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

std::size_t count_containing(const std::vector<std::string>& lines, const std::string& what) {
  return static_cast<std::size_t>(
      std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(what) != std::string::npos; }));
}

std::string coe(const std::string& transition, const std::string& index, int sub, const std::string& data,
                const std::string& extra = {}) {
  return "<InitCmd" + extra + "><Transition>" + transition + "</Transition><Timeout>0</Timeout><Ccs>1</Ccs><Index>" + index +
         "</Index><SubIndex>" + std::to_string(sub) + "</SubIndex><Data>" + data + "</Data></InitCmd>\n";
}

// The built-in A6B (vendor 066Fh, product 60380005h) with these CoE and register init commands.
std::string a6b_with(const std::string& coe_cmds, const std::string& register_cmds = {}) {
  return "<EtherCATConfig><Config>\n"                                                                     // 1
         "<Slave><Info><Name>Axis</Name><PhysAddr>1001</PhysAddr><VendorId>1647</VendorId>"
         "<ProductCode>1614282757</ProductCode><RevisionNo>65536</RevisionNo></Info>\n"                   // 2
         "<Mailbox><Send><Start>4096</Start><Length>128</Length></Send><Recv><Start>4352</Start><Length>128</Length></Recv>"
         "<Protocol>CoE</Protocol><CoE><InitCmds>\n" +                                                    // 3
         coe_cmds + "</InitCmds></CoE></Mailbox>\n<InitCmds>\n" + register_cmds +
         "</InitCmds></Slave></Config></EtherCATConfig>\n";
}

TEST(EniInitCommands, TheStartUpSequenceIsAccepted) {
  const machine::EniNetwork n = machine::parse_eni(a6b_with(coe("PS", "#x1c12", 0, "00") + coe("PS", "#x1c12", 1, "0016") +
                                                            coe("PS", "#x1c12", 0, "01") + coe("PS", "#x6060", 0, "08")),
                                                   "axis.xml", {});
  ASSERT_EQ(n.network.slaves.size(), 1u);
  EXPECT_EQ(n.network.slaves[0].device, "a6b");
  EXPECT_TRUE(n.warnings.empty()) << joined(n.warnings);
}

TEST(EniInitCommands, EachCommandTheDeviceRefusesIsAWarningWithItsAbortCode) {
  const machine::EniNetwork n = machine::parse_eni(
      a6b_with(coe("PS", "#x5fff", 0, "01") +                       // line 4: no such object
               coe("PS", "#x1018", 1, "01000000") +                 // line 5: read-only
               coe("PS", "#x1c12", 1, "0016") +                     // line 6: 1C12h:00h is not 0
               coe("PS", "#x5fff", 1, "01", "><Disabled>1</Disabled") +  // skipped by the master
               "<InitCmd><Transition>PS</Transition><Ccs>2</Ccs><Index>#x5ffe</Index><SubIndex>0</SubIndex></InitCmd>\n"),
      "axis.xml", {});
  const std::vector<std::string>& w = n.warnings;
  EXPECT_EQ(count_containing(w, "CoE init command"), 4u) << joined(w);
  EXPECT_EQ(count_containing(w, "slave 1 'Axis' (vendor 0x0000066F, product 0x60380005, revision 0x00010000): CoE init "
                                "command (line 4, PS): download 5FFFh:00h: the device answers abort 06020000h"), 1u)
      << joined(w);
  EXPECT_EQ(count_containing(w, "(line 5, PS): download 1018h:01h: the device answers abort 06010002h"), 1u) << joined(w);
  EXPECT_EQ(count_containing(w, "(line 6, PS): download 1C12h:01h: the device answers abort 06010003h"), 1u) << joined(w);
  EXPECT_EQ(count_containing(w, "(line 8, PS): upload 5FFEh:00h: the device answers abort 06020000h"), 1u) << joined(w);
  EXPECT_EQ(count_containing(w, "5FFFh:01h"), 0u) << "a disabled command is not sent";
  // Each with the abort's text.
  EXPECT_EQ(count_containing(w, "06020000h (" ), 2u) << joined(w);
}

TEST(EniInitCommands, AnEntryWrittenInTheWrongStateIsRefusedAsTheDeviceDoes) {
  // The A6B takes PDO assignment in Pre-Op only: an SO command is sent in Safe-Op.
  const machine::EniNetwork n = machine::parse_eni(a6b_with(coe("SO", "#x1c12", 0, "00")), "axis.xml", {});
  EXPECT_EQ(count_containing(n.warnings, "(line 4, SO): download 1C12h:00h: the device answers abort"), 1u)
      << joined(n.warnings);
}

TEST(EniInitCommands, MailboxSyncManagersAndDcActivationTheDeviceRefusesAreWarnings) {
  const std::string registers =
      "<InitCmd><Transition>IP</Transition><Cmd>5</Cmd><Adp>1001</Adp><Ado>2048</Ado><Data>0010080026000100</Data></InitCmd>\n"
      "<InitCmd><Transition>IP</Transition><Cmd>5</Cmd><Adp>1001</Adp><Ado>2056</Ado><Data>0011800022000100</Data></InitCmd>\n"
      "<InitCmd><Transition>PS</Transition><Cmd>5</Cmd><Adp>1001</Adp><Ado>2432</Ado><Data>0007</Data></InitCmd>\n";
  const machine::EniNetwork n = machine::parse_eni(a6b_with("", registers), "axis.xml", {});
  const std::vector<std::string>& w = n.warnings;
  ASSERT_EQ(w.size(), 2u) << joined(w);
  EXPECT_NE(w[0].find("SM0 1000h/8 bytes/26h"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("the device refuses Pre-Op with AL status code 0016h"), std::string::npos) << w[0];
  EXPECT_NE(w[1].find("0981h = 07h: the device refuses Safe-Op with AL status code 0030h"), std::string::npos) << w[1];
}

TEST(EniInitCommands, ARegisterSetUpTheDeviceTakesIsNoWarning) {
  const std::string registers =
      "<InitCmd><Transition>IP</Transition><Cmd>5</Cmd><Adp>1001</Adp><Ado>2048</Ado><Data>0010800026000100</Data></InitCmd>\n"
      "<InitCmd><Transition>IP</Transition><Cmd>5</Cmd><Adp>1001</Adp><Ado>2056</Ado><Data>0011800022000100</Data></InitCmd>\n"
      "<InitCmd><Transition>PS</Transition><Cmd>5</Cmd><Adp>1001</Adp><Ado>2432</Ado><Data>0003</Data></InitCmd>\n";
  const machine::EniNetwork n = machine::parse_eni(a6b_with("", registers), "axis.xml", {});
  EXPECT_TRUE(n.warnings.empty()) << joined(n.warnings);
}

TEST(EniInitCommands, CoeCommandsForADeviceWithoutCoeAreOneWarning) {
  // The EL1008-like input terminal of the test ESI files has no mailbox at all.
  const std::string eni =
      "<EtherCATConfig><Config><Slave><Info><Name>DI</Name><PhysAddr>1001</PhysAddr><VendorId>2</VendorId>"
      "<ProductCode>66072658</ProductCode><RevisionNo>1048576</RevisionNo></Info><Mailbox><Send><Start>4096</Start>"
      "<Length>64</Length></Send><Recv><Start>4160</Start><Length>64</Length></Recv><CoE><InitCmds>" +
      coe("PS", "#x8000", 1, "01") + coe("PS", "#x8000", 2, "01") +
      "</InitCmds></CoE></Mailbox></Slave></Config></EtherCATConfig>";
  const machine::EniNetwork n =
      machine::parse_eni(eni, "di.xml", {std::string(VDRIVE_TEST_PRODUCTS_DIR) + "/esi"});
  ASSERT_EQ(n.warnings.size(), 1u) << joined(n.warnings);
  EXPECT_NE(n.warnings[0].find("slave 1 'DI' (vendor 0x00000002, product 0x03F03052, revision 0x00100000): 2 CoE init "
                               "commands, but the device has no CoE"),
            std::string::npos)
      << n.warnings[0];
}

}  // namespace
