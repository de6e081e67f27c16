#pragma once
// One <Slave> of a master's ENI (EtherCATConfig XML, ETG.2100) as the master was told the device
// is: identity, mailbox, process data (SyncManagers, PDOs), distributed clocks and the init
// commands the master sends it (register writes and CoE SDO transfers). Read with tinyxml2 the
// way the ESI reader reads a <Device>; numbers as the file gives them, lines for messages.
// What a slave is matched to, or built from, is decided elsewhere (eni_slave_device.hpp,
// vdrive/machine/eni_reader.hpp).
#include <tinyxml2.h>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vdrive/esi/esi_device.hpp"
#include "vdrive/esi/xml_reading.hpp"

namespace vdrive::esi {

// <InitCmds><InitCmd>: one datagram the master sends at the transitions listed.
struct EniRegisterCommand {
  std::vector<std::string> transitions;  // "IP", "PS", "SO", ... as written
  std::uint8_t cmd = 0;                  // datagram command (ETG.1000.4): 2 APWR, 5 FPWR, 8 BWR ...
  std::uint16_t ado = 0;                 // register address
  std::vector<std::uint8_t> data;        // <Data>, or zeros of <DataLength>
  std::string comment;
  int line = 0;

  bool is_write() const;                 // a command that writes the slave's registers
  bool runs_at(std::string_view transition) const;
};

// <Mailbox><CoE><InitCmds><InitCmd>: an SDO transfer at the transitions listed.
struct EniCoeCommand {
  std::vector<std::string> transitions;
  std::uint8_t ccs = 1;                  // 1 download, 2 upload (ETG.1000.6 client command specifier)
  std::uint16_t index = 0;
  std::uint8_t subindex = 0;
  std::vector<std::uint8_t> data;
  bool complete_access = false;
  bool disabled = false;                 // <Disabled>: the master skips it
  std::string comment;
  int line = 0;
};

// <ProcessData><SmN>: how the master sets SyncManager N up for process data.
struct EniSmSetting {
  int number = 0;
  std::string type;                      // Outputs, Inputs
  std::optional<std::uint16_t> start;    // StartAddress
  std::optional<std::uint16_t> default_size;
  std::optional<std::uint8_t> control;   // ControlByte
  bool enable = true;
  std::vector<std::uint16_t> pdos;       // <Pdo>: the PDOs assigned to it
  int line = 0;
};

// A SyncManager set-up a register init command writes (0800h + 8n: start, length, control,
// status, activate).
struct EniSmWrite {
  std::uint16_t start = 0, length = 0;
  std::uint8_t control = 0;
  bool enable = true;
  int line = 0;
};

struct EniSlave {
  std::string file;
  int line = 0;                          // of <Slave>
  std::string name;                      // <Info><Name>
  std::optional<std::uint16_t> phys_addr;
  std::uint32_t vendor_id = 0, product_code = 0, revision = 0;
  std::string physics;                   // <Info><Physics>: one letter per port
  // <Mailbox>: Send is the master's (SM0, MBoxOut), Recv the slave's (SM1, MBoxIn).
  bool has_mailbox = false;
  int mailbox_line = 0;
  std::uint16_t send_start = 0, send_length = 0, recv_start = 0, recv_length = 0;
  std::vector<std::string> protocols;    // <Protocol> texts and the protocols with their own element
  // <Mailbox><BootStrap>: the Boot-state mailbox, Send (SM0) and Recv (SM1) start and length.
  std::optional<std::array<std::uint16_t, 4>> boot_mailbox;
  // <ProcessData>
  int process_data_line = 0;
  std::uint32_t output_bits = 0, input_bits = 0;  // <Send>/<Recv> BitLength
  std::vector<EniSmSetting> sms;
  std::vector<EsiPdo> rx_pdos, tx_pdos;
  // <DC>
  bool has_dc = false;
  int dc_line = 0;
  bool reference_clock = false;
  std::uint32_t cycle_time0 = 0;
  std::vector<EniRegisterCommand> init_commands;
  std::vector<EniCoeCommand> coe_init_commands;

  bool has_protocol(std::string_view p) const;
  // SyncManager n as its register init commands set it up: the first write that gives it a
  // length (ENIs also clear SyncManagers with zeros).
  std::optional<EniSmWrite> sm_written(int n) const;
  // The DC activation its register init commands write (0980h/0981h), as ESI AssignActivate
  // (0981h in the high byte); nullopt when none activates anything.
  std::optional<std::uint16_t> dc_activation() const;
};

// Reads one <Slave>; what it cannot read is an EsiError naming file, line and element.
EniSlave read_eni_slave(const XmlReading& xml, const tinyxml2::XMLElement* slave);

}  // namespace vdrive::esi
