#include "master/mailbox.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "master/registers.hpp"

namespace vdrive::master {

namespace {
constexpr std::uint16_t kSm1 = reg::kSm0 + reg::kSmSize;
constexpr std::uint16_t kSm0Status = reg::kSm0 + 5;
constexpr std::uint16_t kSm1Status = kSm1 + 5;
constexpr std::uint16_t kSm1Activate = kSm1 + reg::kSmActivateOffset;
constexpr std::uint16_t kSm1PdiControl = kSm1 + 7;
constexpr std::uint8_t kSmStatusMailboxFull = 0x08;
constexpr std::uint8_t kRepeatBit = 0x02;
constexpr std::uint8_t kCoEServiceEmergency = 1;
}  // namespace

std::string_view mailbox_error_text(std::uint16_t code) {
  switch (code) {
    case 0x01: return "MBXERR_SYNTAX";
    case 0x02: return "MBXERR_UNSUPPORTEDPROTOCOL";
    case 0x03: return "MBXERR_INVALIDCHANNEL";
    case 0x04: return "MBXERR_SERVICENOTSUPPORTED";
    case 0x05: return "MBXERR_INVALIDHEADER";
    case 0x06: return "MBXERR_SIZETOOSHORT";
    case 0x07: return "MBXERR_NOMOREMEMORY";
    case 0x08: return "MBXERR_INVALIDSIZE";
    default: return "unknown mailbox error";
  }
}

MailboxClient::MailboxClient(Transport& transport, const MailboxConfig& config, Nanos timeout, std::uint8_t* counter)
    : transport_(transport),
      config_(config),
      timeout_(timeout),
      counter_(counter != nullptr ? counter : &own_counter_),
      out_(config.rx_size),
      in_(config.tx_size) {
  if (config.rx_size <= kMailboxHeaderSize || config.tx_size <= kMailboxHeaderSize) {
    throw MailboxError(fmt::format("slave 0x{:04X} has no usable mailbox", config.station));
  }
}

void MailboxClient::sleep_poll() {
  // 100 us between polls: in the link's wait, so a virtual line moves its time meanwhile.
  transport_.idle_until(transport_.clock().now() + 100'000);
}

void MailboxClient::send(std::uint8_t type, std::span<const std::uint8_t> payload) {
  if (payload.size() > max_payload()) {
    throw MailboxError(fmt::format("slave 0x{:04X}: {} bytes do not fit the {}-byte mailbox", config_.station,
                                   payload.size(), config_.rx_size));
  }
  // SM0 must be empty: the slave has taken the previous message.
  const Nanos deadline = transport_.clock().now() + timeout_;
  for (;;) {
    const auto status = transport_.fprd_value<std::uint8_t>(config_.station, kSm0Status);
    if (status && (*status & kSmStatusMailboxFull) == 0) break;
    if (transport_.clock().now() >= deadline) {
      throw MailboxError(fmt::format("slave 0x{:04X}: mailbox SM0 stays full", config_.station));
    }
    sleep_poll();
  }
  *counter_ = static_cast<std::uint8_t>(*counter_ % 7 + 1);  // 1..7; 0 is reserved for "no counter"
  std::fill(out_.begin(), out_.end(), 0);
  const auto length = static_cast<std::uint16_t>(payload.size());
  out_[0] = static_cast<std::uint8_t>(length);
  out_[1] = static_cast<std::uint8_t>(length >> 8);
  out_[2] = out_[3] = 0;   // address: 0 = from the master
  out_[4] = 0;             // channel 0, priority 0
  out_[5] = static_cast<std::uint8_t>((type & 0x0F) | (*counter_ << 4));
  std::copy(payload.begin(), payload.end(), out_.begin() + kMailboxHeaderSize);
  // The whole buffer: the ESC completes the write only when its last byte is written.
  const Wkc wkc = transport_.fpwr(config_.station, config_.rx_offset, out_);
  if (!wkc || *wkc != 1) {
    throw MailboxError(fmt::format("slave 0x{:04X}: mailbox write not taken (working counter {})", config_.station,
                                   wkc ? static_cast<int>(*wkc) : -1));
  }
}

bool MailboxClient::sm1_full() {
  const auto status = transport_.fprd_value<std::uint8_t>(config_.station, kSm1Status);
  return status && (*status & kSmStatusMailboxFull) != 0;
}

bool MailboxClient::read_sm1(std::size_t& length, std::uint8_t& type) {
  const Wkc wkc = transport_.fprd(config_.station, config_.tx_offset, in_);
  if (!wkc || *wkc != 1) return false;  // emptied meanwhile or lost: poll again
  length = static_cast<std::size_t>(in_[0] | (in_[1] << 8));
  type = static_cast<std::uint8_t>(in_[5] & 0x0F);
  if (length > in_.size() - kMailboxHeaderSize) {
    throw MailboxError(fmt::format("slave 0x{:04X}: reply length {} exceeds the {}-byte mailbox", config_.station, length,
                                   in_.size()));
  }
  return true;
}

void MailboxClient::repeat_request() {
  // Toggle 0x080E bit 1 and wait until the slave toggles 0x080F bit 1 to the same value.
  ++repeats_;
  const auto activate = transport_.fprd_value<std::uint8_t>(config_.station, kSm1Activate);
  if (!activate) return;
  const auto toggled = static_cast<std::uint8_t>(*activate ^ kRepeatBit);
  transport_.fpwr_value<std::uint8_t>(config_.station, kSm1Activate, toggled);
  const Nanos deadline = transport_.clock().now() + timeout_ / 4;
  while (transport_.clock().now() < deadline) {
    const auto ack = transport_.fprd_value<std::uint8_t>(config_.station, kSm1PdiControl);
    if (ack && ((*ack ^ toggled) & kRepeatBit) == 0) return;
    sleep_poll();
  }
}

void MailboxClient::flush() {
  std::size_t length = 0;
  std::uint8_t type = 0;
  for (int i = 0; i < 8 && sm1_full(); ++i) read_sm1(length, type);
}

std::span<const std::uint8_t> MailboxClient::receive(std::uint8_t wanted) {
  Nanos deadline = transport_.clock().now() + timeout_;
  bool repeated = false;
  for (;;) {
    if (sm1_full()) {
      std::size_t length = 0;
      std::uint8_t type = 0;
      if (read_sm1(length, type)) {
        const auto counter = static_cast<std::uint8_t>((in_[5] >> 4) & 0x07);
        if (counter != 0 && counter == last_received_) continue;  // the same message again
        last_received_ = counter;
        const std::span<const std::uint8_t> payload(in_.data() + kMailboxHeaderSize, length);
        if (type == wanted && !(type == mailbox_type::kCoE && length >= 2 && (payload[1] >> 4) == kCoEServiceEmergency)) {
          return payload;
        }
        if (type == mailbox_type::kError) {
          const std::uint16_t code = length >= 4 ? static_cast<std::uint16_t>(payload[2] | (payload[3] << 8)) : 0;
          throw MailboxError(fmt::format("slave 0x{:04X}: mailbox error 0x{:04X} ({})", config_.station, code,
                                         mailbox_error_text(code)),
                             code);
        }
        if (type == mailbox_type::kCoE && length >= 10 && (payload[1] >> 4) == kCoEServiceEmergency) {
          Emergency e;
          e.station = config_.station;
          e.error_code = static_cast<std::uint16_t>(payload[2] | (payload[3] << 8));
          e.error_register = payload[4];
          std::copy(payload.begin() + 5, payload.begin() + 10, e.data.begin());
          if (emergencies_.size() >= 64) emergencies_.pop_front();
          emergencies_.push_back(e);
        }
        continue;  // not ours: keep waiting
      }
    }
    if (transport_.clock().now() >= deadline) {
      if (repeated) {
        throw MailboxError(fmt::format("slave 0x{:04X}: no mailbox reply", config_.station));
      }
      // The reply may have been lost on the wire (read but its frame never came back).
      repeat_request();
      repeated = true;
      deadline = transport_.clock().now() + timeout_;
    }
    sleep_poll();
  }
}

}  // namespace vdrive::master
