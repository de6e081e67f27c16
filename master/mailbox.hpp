#pragma once
// The project master keeps its own copy of this EtherCAT vocabulary on purpose, written from the
// specification and not shared with ethercat/: it is the independent test oracle of the slave, so a
// wrong value in one is caught by the other.
// Mailbox client of one slave over SM0 (master -> slave) and SM1 (slave -> master), ETG.1000.4
// clause 5.6 / ETG.1000.6 clause 5.6:
//
//   header: length (2), address (2), channel:6 priority:2 (1), type:4 counter:3 reserved:1 (1)
//
// send() writes one whole SM0 buffer (the ESC only hands it to the slave when the last byte is
// written) with the next counter 1..7. receive() polls SM1's status byte 0x080D (bit 3: mailbox
// full) with FPRD, reads the whole SM1 buffer and returns its payload. When no reply comes within
// the timeout it toggles the repeat request (0x080E bit 1), waits for the slave's acknowledge
// (0x080F bit 1) and polls again: the slave then re-sends its last reply. CoE emergencies that
// arrive while waiting for something else are queued (emergencies()). A mailbox error reply
// (type 0) becomes MailboxError with its ETG.1000.6 Table 28 code. A message whose counter
// (1..7) repeats the one received just before is the slave sending it twice and is dropped
// (ETG.1000.4); restarted() forgets that counter when the slave's mailbox starts again.
//
// Buffers are the slave's mailbox sizes, allocated once in the constructor.
#include <cstdint>
#include <deque>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/clock.hpp"
#include "master/transport.hpp"

namespace vdrive::master {

namespace mailbox_type {
constexpr std::uint8_t kError = 0x00, kAoE = 0x01, kEoE = 0x02, kCoE = 0x03, kFoE = 0x04, kSoE = 0x05,
                       kVoE = 0x0F;
}
constexpr std::size_t kMailboxHeaderSize = 6;

class MailboxError : public std::runtime_error {
public:
  MailboxError(std::string what, std::uint16_t code = 0) : std::runtime_error(std::move(what)), code_(code) {}
  // Mailbox error code (ETG.1000.6 Table 28) when the slave sent a mailbox error reply, else 0.
  std::uint16_t code() const { return code_; }

private:
  std::uint16_t code_;
};

// "MBXERR_INVALIDHEADER" style names for mailbox error codes.
std::string_view mailbox_error_text(std::uint16_t code);

// A CoE emergency message (ETG.1000.6 5.6.2.7.1): error code, error register, 5 vendor bytes.
struct Emergency {
  std::uint16_t station = 0;
  std::uint16_t error_code = 0;
  std::uint8_t error_register = 0;
  std::array<std::uint8_t, 5> data{};
};

struct MailboxConfig {
  std::uint16_t station = 0;
  std::uint16_t rx_offset = 0, rx_size = 0;   // SM0: master writes
  std::uint16_t tx_offset = 0, tx_size = 0;   // SM1: master reads
};

class MailboxClient {
public:
  // `counter`: the slave's mailbox counter (Slave::mailbox_counter) when several clients talk to
  // one slave in turn. A slave drops a message whose counter repeats the previous one's as a
  // duplicate (ETG.1000.4), so a new client must continue the sequence, not restart it at 1.
  // nullptr: the client counts on its own. The counter must outlive the client.
  MailboxClient(Transport& transport, const MailboxConfig& config, Nanos timeout = 1'000'000'000,
                std::uint8_t* counter = nullptr);
  MailboxClient(const MailboxClient&) = delete;  // counter_ may point into the object
  MailboxClient& operator=(const MailboxClient&) = delete;

  // Largest payload one message carries (mailbox size minus the 6-byte header).
  std::size_t max_payload() const { return config_.rx_size - kMailboxHeaderSize; }
  std::size_t max_reply_payload() const { return config_.tx_size - kMailboxHeaderSize; }

  // Writes one message; waits (up to the timeout) while SM0 is still full. Throws MailboxError.
  void send(std::uint8_t type, std::span<const std::uint8_t> payload);
  // Waits for the next message of `type` and returns its payload (valid until the next call).
  // Emergencies met on the way are queued; other types are dropped. Throws MailboxError.
  std::span<const std::uint8_t> receive(std::uint8_t type);
  // Reads and discards whatever SM1 holds now (a stale reply of an earlier master).
  void flush();
  // The slave's mailbox was set up again (Init -> Pre-Op/Boot): its reply counter starts anew.
  void restarted() { last_received_ = 0; }

  std::deque<Emergency>& emergencies() { return emergencies_; }
  std::uint64_t repeat_requests() const { return repeats_; }
  const MailboxConfig& config() const { return config_; }
  Nanos timeout() const { return timeout_; }

private:
  bool sm1_full();
  bool read_sm1(std::size_t& length, std::uint8_t& type);
  void repeat_request();
  void sleep_poll();

  Transport& transport_;
  MailboxConfig config_;
  Nanos timeout_;
  std::uint8_t own_counter_ = 0;
  std::uint8_t* counter_;  // last counter sent (1..7): own_counter_ or the slave's
  std::vector<std::uint8_t> out_, in_;
  std::deque<Emergency> emergencies_;
  std::uint64_t repeats_ = 0;
  std::uint8_t last_received_ = 0;  // counter of the last message taken from SM1, 0 = none
};

}  // namespace vdrive::master
