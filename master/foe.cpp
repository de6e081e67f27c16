#include "master/foe.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "master/master.hpp"

namespace vdrive::master {

namespace {
constexpr std::uint8_t kRrq = 1, kWrq = 2, kData = 3, kAck = 4, kErr = 5, kBusy = 6;

std::uint32_t u32(std::span<const std::uint8_t> p, std::size_t at) {
  return static_cast<std::uint32_t>(p[at]) | (static_cast<std::uint32_t>(p[at + 1]) << 8) |
         (static_cast<std::uint32_t>(p[at + 2]) << 16) | (static_cast<std::uint32_t>(p[at + 3]) << 24);
}

std::span<const std::uint8_t> name_bytes(std::string_view name) {
  return {reinterpret_cast<const std::uint8_t*>(name.data()), name.size()};
}

// A reply shorter than the FoE header is a protocol error of the slave.
std::span<const std::uint8_t> checked(std::span<const std::uint8_t> reply, std::uint16_t station) {
  if (reply.size() < FoeClient::kFoeHeaderSize) {
    throw MailboxError(fmt::format("slave 0x{:04X}: FoE reply of {} bytes", station, reply.size()));
  }
  return reply;
}

MailboxConfig current_config(Master& master, std::size_t slave) {
  master.read_al_status(slave);
  return foe_mailbox_config(master.slaves().at(slave));
}

[[noreturn]] void throw_slave_error(std::span<const std::uint8_t> reply) {
  std::string text(reply.begin() + FoeClient::kFoeHeaderSize, reply.end());
  text.erase(std::find(text.begin(), text.end(), '\0'), text.end());
  throw FoeError(u32(reply, 2), std::move(text));
}
}  // namespace

std::string_view foe_error_text(std::uint32_t code) {
  switch (code) {
    case foe_error::kNotDefined: return "Not defined";
    case foe_error::kNotFound: return "Not found";
    case foe_error::kAccessDenied: return "Access denied";
    case foe_error::kDiskFull: return "Disk full";
    case foe_error::kIllegal: return "Illegal";
    case foe_error::kPacketNumberWrong: return "Packet number wrong";
    case foe_error::kAlreadyExists: return "Already exists";
    case foe_error::kNoUser: return "No user";
    case foe_error::kBootstrapOnly: return "Bootstrap only";
    case foe_error::kNotBootstrap: return "Not Bootstrap";
    case foe_error::kNoRights: return "No rights";
    case foe_error::kProgramError: return "Program error";
    case foe_error::kChecksumError: return "Checksum error";
    case foe_error::kFirmwareDoesNotFit: return "Firmware does not fit for hardware";
    case foe_error::kNoFileToRead: return "No file to read";
    default: return "unknown FoE error";
  }
}

FoeError::FoeError(std::uint32_t code, std::string slave_text)
    // The slave's text only where it says more than the code's name.
    : std::runtime_error(fmt::format("FoE error 0x{:04X} ({}){}{}", code, foe_error_text(code),
                                     slave_text.empty() || slave_text == foe_error_text(code) ? "" : ": ",
                                     slave_text == foe_error_text(code) ? "" : slave_text)),
      code_(code),
      slave_text_(std::move(slave_text)) {}

MailboxConfig foe_mailbox_config(const Slave& s) {
  if (s.state() == AlState::Boot) {
    return {s.station, s.info.boot_rx_offset, s.info.boot_rx_size, s.info.boot_tx_offset, s.info.boot_tx_size};
  }
  return {s.station, s.mailbox_sm[0].start, s.mailbox_sm[0].length, s.mailbox_sm[1].start, s.mailbox_sm[1].length};
}

FoeClient::FoeClient(Transport& transport, const MailboxConfig& config, FoeOptions options, std::uint8_t* counter)
    : transport_(transport), mailbox_(transport, config, options.timeout, counter), options_(std::move(options)) {
  if (mailbox_.max_payload() <= kFoeHeaderSize) {
    throw MailboxError(fmt::format("slave 0x{:04X}: mailbox too small for FoE", config.station));
  }
}

FoeClient::FoeClient(Master& master, std::size_t slave, FoeOptions options)
    : FoeClient(master.transport(), current_config(master, slave), std::move(options),
                &master.slaves().at(slave).mailbox_counter) {}

void FoeClient::send(std::uint8_t op, std::uint32_t field, std::span<const std::uint8_t> tail) {
  message_.assign({op, 0, static_cast<std::uint8_t>(field), static_cast<std::uint8_t>(field >> 8),
                   static_cast<std::uint8_t>(field >> 16), static_cast<std::uint8_t>(field >> 24)});
  message_.insert(message_.end(), tail.begin(), tail.end());
  mailbox_.send(mailbox_type::kFoE, message_);
}

void FoeClient::write(std::string_view name, std::span<const std::uint8_t> data, std::uint32_t password) {
  mailbox_.flush();  // a reply left over from an earlier exchange is not ours
  send(kWrq, password, name_bytes(name.substr(0, max_data())));
  const auto reply = checked(mailbox_.receive(mailbox_type::kFoE), mailbox_.config().station);
  if (reply[0] == kErr) throw_slave_error(reply);
  if (reply[0] != kAck || u32(reply, 2) != 0) {
    throw MailboxError(fmt::format("slave 0x{:04X}: FoE write request answered with op code {}",
                                   mailbox_.config().station, reply[0]));
  }
  const std::size_t full = max_data();
  std::size_t at = 0;
  for (std::uint32_t packet = 1;; ++packet) {
    const std::size_t n = std::min(full, data.size() - at);
    send_data_until_acked(packet, data.subspan(at, n));
    at += n;
    if (options_.progress) options_.progress(at, data.size());
    if (n < full) return;  // a short (or empty) packet ended the file
  }
}

// One DATA packet until its ACK: sent again when the ACK is lost or the slave is busy.
void FoeClient::send_data_until_acked(std::uint32_t packet, std::span<const std::uint8_t> data) {
  const Nanos busy_deadline = transport_.clock().now() + options_.busy_timeout;
  int resends = 0;
  for (;;) {
    send(kData, packet, data);
    std::span<const std::uint8_t> reply;
    try {
      reply = checked(mailbox_.receive(mailbox_type::kFoE), mailbox_.config().station);
    } catch (const MailboxError& e) {
      if (e.code() != 0 || resends >= options_.resends) throw;  // a mailbox error reply, or given up
      ++resends;
      ++resent_;
      continue;  // no reply even after the mailbox repeat: the ACK is lost, send the packet again
    }
    if (reply[0] == kErr) throw_slave_error(reply);
    if (reply[0] == kAck && u32(reply, 2) == packet) return;
    if (reply[0] == kBusy) {
      ++busy_;
      if (transport_.clock().now() >= busy_deadline) {
        throw MailboxError(fmt::format("slave 0x{:04X}: FoE busy for too long", mailbox_.config().station));
      }
      transport_.idle_until(transport_.clock().now() + options_.busy_pause);
      continue;
    }
    throw MailboxError(fmt::format("slave 0x{:04X}: FoE packet {} answered with op code {} / number {}",
                                   mailbox_.config().station, packet, reply[0], u32(reply, 2)));
  }
}

std::vector<std::uint8_t> FoeClient::read(std::string_view name, std::uint32_t password) {
  mailbox_.flush();
  send(kRrq, password, name_bytes(name.substr(0, max_data())));
  const std::size_t full = mailbox_.max_reply_payload() - kFoeHeaderSize;
  std::vector<std::uint8_t> file;
  std::uint32_t expected = 1;
  for (;;) {
    const auto reply = checked(mailbox_.receive(mailbox_type::kFoE), mailbox_.config().station);
    if (reply[0] == kErr) throw_slave_error(reply);
    if (reply[0] == kBusy) continue;  // the slave prepares the file: its DATA follows
    if (reply[0] != kData) {
      throw MailboxError(fmt::format("slave 0x{:04X}: FoE read answered with op code {}", mailbox_.config().station,
                                     reply[0]));
    }
    const std::uint32_t packet = u32(reply, 2);
    if (packet + 1 == expected) {  // our ACK was lost and the slave sent the packet again
      send(kAck, packet, {});
      continue;
    }
    if (packet != expected) {
      const std::string_view text = foe_error_text(foe_error::kPacketNumberWrong);
      send(kErr, foe_error::kPacketNumberWrong, name_bytes(text));
      throw FoeError(foe_error::kPacketNumberWrong, fmt::format("slave sent packet {}, expected {}", packet, expected));
    }
    const std::size_t n = reply.size() - kFoeHeaderSize;
    file.insert(file.end(), reply.begin() + kFoeHeaderSize, reply.end());
    send(kAck, packet, {});
    if (n < full) return file;
    ++expected;
  }
}

}  // namespace vdrive::master
