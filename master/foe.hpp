#pragma once
// The project master keeps its own copy of this EtherCAT vocabulary on purpose, written from the
// specification and not shared with ethercat/: it is the independent test oracle of the slave, so a
// wrong value in one is caught by the other.
// FoE client of one slave (ETG.1000.6 5.7, File Access over EtherCAT) on its own MailboxClient:
//
//  - write(): WRQ (password + file name), then DATA packets 1, 2, ... of (mailbox size - 12)
//    bytes, each acknowledged before the next; a packet shorter than that ends the file (an empty
//    one after a file of whole packets). A DATA whose ACK never comes (lost on the wire, after
//    the mailbox repeat request too) is sent again with the same packet number; BUSY makes the
//    client wait and repeat the packet until the slave acknowledges it.
//  - read(): RRQ, then the slave's DATA packets, each acknowledged; a short one ends the file.
//  - The slave's ERR reply becomes FoeError (code 0x8000.. and the slave's text); a mailbox
//    error reply (e.g. 0x0002, a product without FoE) stays MailboxError.
//
// Which mailbox: in Boot the SII's bootstrap mailbox (words 14h-17h), else SM0/SM1 as the
// master configured them. Configuration-time code: it allocates.
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "master/mailbox.hpp"

namespace vdrive::master {

class Master;
struct Slave;

namespace foe_error {
constexpr std::uint32_t kNotDefined = 0x8000, kNotFound = 0x8001, kAccessDenied = 0x8002, kDiskFull = 0x8003,
                        kIllegal = 0x8004, kPacketNumberWrong = 0x8005, kAlreadyExists = 0x8006, kNoUser = 0x8007,
                        kBootstrapOnly = 0x8008, kNotBootstrap = 0x8009, kNoRights = 0x800A,
                        kProgramError = 0x800B, kChecksumError = 0x800C, kFirmwareDoesNotFit = 0x800D,
                        kNoFileToRead = 0x800F;
}

// ETG.1000.6 name of an FoE error code ("Packet number wrong", ...).
std::string_view foe_error_text(std::uint32_t code);

class FoeError : public std::runtime_error {
public:
  FoeError(std::uint32_t code, std::string slave_text);
  std::uint32_t code() const { return code_; }
  const std::string& slave_text() const { return slave_text_; }

private:
  std::uint32_t code_;
  std::string slave_text_;
};

struct FoeOptions {
  Nanos timeout = 1'000'000'000;        // per reply (the mailbox client's timeout)
  int resends = 3;                      // times one DATA packet is sent again when its ACK is lost
  Nanos busy_pause = 1'000'000;         // wait after BUSY before repeating the packet
  Nanos busy_timeout = 30'000'000'000;  // give up when the slave stays busy this long
  std::function<void(std::size_t done, std::size_t total)> progress;  // after each ACK (write)
};

// The mailbox the slave uses in its current state (slave.al as last read).
MailboxConfig foe_mailbox_config(const Slave& slave);

class FoeClient {
public:
  // `counter`: the slave's mailbox counter, see MailboxClient.
  FoeClient(Transport& transport, const MailboxConfig& config, FoeOptions options = {},
            std::uint8_t* counter = nullptr);
  // The slave's mailbox for its current AL state (reads AL status first), continuing the counter
  // of the master's other clients of that slave (Slave::mailbox_counter).
  FoeClient(Master& master, std::size_t slave, FoeOptions options = {});

  // Throws FoeError (the slave's ERR), MailboxError (mailbox error reply, timeout).
  void write(std::string_view name, std::span<const std::uint8_t> data, std::uint32_t password = 0);
  std::vector<std::uint8_t> read(std::string_view name, std::uint32_t password = 0);

  // Data bytes per DATA packet the client sends (mailbox size - 12).
  std::size_t max_data() const { return mailbox_.max_payload() - kFoeHeaderSize; }
  std::uint64_t resent_packets() const { return resent_; }
  std::uint64_t busy_replies() const { return busy_; }
  MailboxClient& mailbox() { return mailbox_; }

  static constexpr std::size_t kFoeHeaderSize = 6;

private:
  void send(std::uint8_t op, std::uint32_t field, std::span<const std::uint8_t> tail);
  void send_data_until_acked(std::uint32_t packet, std::span<const std::uint8_t> data);

  Transport& transport_;
  MailboxClient mailbox_;
  FoeOptions options_;
  std::vector<std::uint8_t> message_;
  std::uint64_t resent_ = 0, busy_ = 0;
};

}  // namespace vdrive::master
