#include "vdrive/firmware/mailbox/mailbox_module.hpp"

#include <algorithm>
#include <array>

#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"
#include "ethercat/sii.hpp"
#include "vdrive/firmware/coe/coe_server.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"
#include "vdrive/firmware/pdi.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::mailbox {

using ecat::mailbox::ErrorCode;
using ecat::mailbox::Header;
using ecat::mailbox::kErrorPayloadSize;
using ecat::mailbox::kHeaderSize;
using ecat::mailbox::next_counter;
using ecat::mailbox::Type;

namespace {
constexpr std::uint32_t sm_event(int n) { return 1u << (al_event::kSmShift + n); }
constexpr std::size_t kMinimumWindow = kHeaderSize + 16;  // header + an SDO frame with margin

std::size_t larger(std::uint16_t a, const std::optional<std::uint16_t>& b) {
  return std::max<std::size_t>(a, b.value_or(0));
}
}  // namespace

MailboxModule::MailboxModule(FirmwareContext& context, const MailboxOptions& options)
    : context_(context),
      request_(larger(context.profile.mailbox.rx_size, context.profile.mailbox.boot_rx_size)),
      // One slot more than we fill, so a reply displaced by a repeat request always fits back.
      queue_(kReplySlots + 1,
             larger(context.profile.mailbox.tx_size, context.profile.mailbox.boot_tx_size)),
      sent_(larger(context.profile.mailbox.tx_size, context.profile.mailbox.boot_tx_size)),
      previous_(sent_.size()),
      zeros_(sent_.size()),
      resend_(sent_.size()) {
  coe_ = std::make_unique<coe::CoeServer>(context, options.state_dir);
  if (context.profile.foe_details != 0) {
    foe_ = std::make_unique<foe::FoeServer>(
        context, foe::FoeOptions{options.state_dir, options.foe_max_file_bytes, options.foe_programming_time});
  }
}

MailboxModule::~MailboxModule() = default;

// SM1's event is not in the fixed set: the module unmasks it itself while it needs it (watch_sm1).
std::uint32_t MailboxModule::serviced_events() const {
  if (!context_.profile.has_mailbox()) return 0;  // a device without one: SM0 is process data
  return sm_event(0) | al_event::kSmActivation;
}

void MailboxModule::on_events(std::uint32_t events, Nanos now) {
  if (!running_) return;
  if (events & al_event::kSmActivation) service_repeat_request();
  if (events & (sm_event(0) | sm_event(1))) service(now);
  watch_sm1(has_outgoing());
}

// The ESC keeps SM1's read event set while the mailbox is idle (the master read the last
// message), so a level-triggered PDI interrupt with it unmasked would fire on every pass of the
// firmware's loop. As firmware must, the event is unmasked only while a message waits for SM1 to
// be read (read-modify-write of 0x0204: the other bits belong to other modules).
void MailboxModule::watch_sm1(bool on) {
  if (on == sm1_watched_) return;
  const std::uint32_t mask = context_.pdi.read_u32(reg::kAlEventMask);
  context_.pdi.write_u32(reg::kAlEventMask, on ? mask | sm_event(1) : mask & ~sm_event(1));
  sm1_watched_ = on;
}

void MailboxModule::entered(ecat::AlState from, ecat::AlState to, Nanos now) {
  if (to == ecat::AlState::Init) {
    // The mailbox stops and forgets its exchange; emergencies stay buffered (A6B L4565).
    running_ = false;
    queue_.clear();
    coe_->reset();
    if (foe_) {
      foe_->reset();
      // Boot -> Init restarts the drive: it runs the firmware downloaded in Boot.
      if (from == ecat::AlState::Boot) foe_->restart();
    }
    last_request_counter_ = 0;
    reply_counter_ = 0;
    sent_length_ = previous_length_ = 0;
    duplicate_pending_ = false;
    watch_sm1(false);
    return;
  }
  if (from != ecat::AlState::Init || !context_.profile.has_mailbox()) return;
  running_ = true;
  boot_ = to == ecat::AlState::Boot;
  service(now);
  watch_sm1(has_outgoing());
}

void MailboxModule::power_on(Nanos now) {
  entered(ecat::AlState::Init, ecat::AlState::Init, now);
  emergency_head_ = emergency_count_ = 0;
  coe_->parameters().power_on();
  if (foe_) foe_->power_on();
}

void MailboxModule::post_emergency(const ecat::coe::Emergency& emergency) {
  if (emergency_count_ == kEmergencySlots) {  // full: the oldest is dropped
    emergency_head_ = (emergency_head_ + 1) % kEmergencySlots;
    --emergency_count_;
  }
  emergencies_[(emergency_head_ + emergency_count_) % kEmergencySlots] = emergency;
  ++emergency_count_;
  if (!running_) return;
  send_next();
  watch_sm1(has_outgoing());
}

bool MailboxModule::sm_full(int n) {
  return (context_.pdi.read_u8(sm_register(n, reg::sm::kStatus)) & reg::sm::kMailboxFull) != 0;
}

bool MailboxModule::has_outgoing() const {
  return !queue_.empty() || emergency_count_ > 0 || duplicate_pending_;
}

// SM windows as the master configured them (start/length/control/status: no side effect).
void MailboxModule::service(Nanos now) {
  const SmChannel sm0 = context_.pdi.read_sm_window(0);
  const SmChannel sm1 = context_.pdi.read_sm_window(1);
  sm0_start_ = sm0.start;
  sm0_length_ = sm0.length;
  sm1_start_ = sm1.start;
  sm1_length_ = sm1.length;
  reply_capacity_ = std::min<std::size_t>(sm1_length_, sent_.size());
  // Smaller windows than any SDO frame are refused at Init->PreOp by the product's rules; the
  // guard keeps the reply arithmetic safe whatever the master configured.
  if (reply_capacity_ < kMinimumWindow || sm0_length_ < kMinimumWindow) return;
  // With no request in SM0 and nothing to send there is nothing more to do.
  if ((sm0.status & reg::sm::kMailboxFull) == 0 && !has_outgoing()) {
    queue_fragments();
    if (!has_outgoing()) return;
  }
  send_next();
  while (queue_.size() < kReplySlots && sm_full(0)) {
    receive_request(now);
    send_next();
  }
  queue_fragments();
  send_next();
}

bool MailboxModule::receive_request(Nanos now) {
  const std::size_t n = std::min<std::size_t>(sm0_length_, request_.size());
  context_.pdi.read(sm0_start_, std::span<std::uint8_t>(request_.data(), n));
  if (n < sm0_length_) {
    // Only the last byte hands the buffer back; what lies beyond our buffer is not a request
    // we could accept anyway (the header check below rejects such a length).
    std::array<std::uint8_t, 1> last{};
    context_.pdi.read(static_cast<std::uint16_t>(sm0_start_ + sm0_length_ - 1), last);
  }
  const Header header = Header::decode(request_);
  if (header.type == static_cast<std::uint8_t>(Type::Error) || header.length == 0) {
    queue_error(ErrorCode::InvalidHeader);
    return true;
  }
  if (header.length > n - kHeaderSize) {
    queue_error(ErrorCode::InvalidSize);
    return true;
  }
  // A repeated counter is the master sending the same request again (it missed our working
  // counter): the request was already served, so it is dropped (ETG.1000.4). 0 = not counted.
  if (header.counter != 0 && header.counter == last_request_counter_) return true;
  last_request_counter_ = header.counter;
  dispatch(header, std::span<const std::uint8_t>(request_.data() + kHeaderSize, header.length),
           now);
  return true;
}

void MailboxModule::dispatch(const Header& header, std::span<const std::uint8_t> payload,
                             Nanos now) {
  const bool coe = header.type == static_cast<std::uint8_t>(Type::CoE) &&
                   (context_.profile.mailbox.protocols & ecat::sii::mailbox_protocol::kCoE) != 0;
  // FoE only where the SII's FoE details advertise it: the A6B's protocol word has the FoE bit
  // but the product has no FoE (L656, L705), so the bit alone does not decide.
  const bool foe = header.type == static_cast<std::uint8_t>(Type::FoE) && foe_ != nullptr;
  if (foe) {
    foe_->set_request_window(sm0_length_);
    queue_reply(*foe_, Type::FoE, payload, now);
    return;
  }
  // In Boot only FoE runs (ETG.1000.6); everything else is "unsupported protocol".
  if (!coe || boot_) {
    queue_error(ErrorCode::UnsupportedProtocol);
    return;
  }
  if (inject_abort(payload)) return;
  queue_reply(*coe_, Type::CoE, payload, now);
}

void MailboxModule::queue_reply(Protocol& protocol, Type type, std::span<const std::uint8_t> payload,
                                Nanos now) {
  const std::span<std::uint8_t> slot = queue_.back_slot();
  const Outcome outcome = protocol.on_request(
      payload, slot.subspan(kHeaderSize, reply_capacity_ - kHeaderSize), now);
  if (outcome.error) {
    queue_error(*outcome.error);
    return;
  }
  if (outcome.length == 0) return;
  if (type == Type::CoE) inject_toggle_error(slot.subspan(kHeaderSize, outcome.length));
  reply_counter_ = next_counter(reply_counter_);
  Header{static_cast<std::uint16_t>(outcome.length), 0, 0, 0, static_cast<std::uint8_t>(type),
         reply_counter_}
      .encode(slot);
  queue_.commit_back(kHeaderSize + outcome.length);
}

void MailboxModule::queue_error(ErrorCode code) {
  const std::span<std::uint8_t> slot = queue_.back_slot();
  reply_counter_ = next_counter(reply_counter_);
  Header{kErrorPayloadSize, 0, 0, 0, static_cast<std::uint8_t>(Type::Error), reply_counter_}
      .encode(slot);
  ecat::mailbox::encode_error_payload(slot.subspan(kHeaderSize, kErrorPayloadSize), code);
  queue_.commit_back(kHeaderSize + kErrorPayloadSize);
}

// Injected abort_code: the SDO request is not served; an abort of that code answers it, for the
// request's index and subindex (a segment carries none: 0000h:00).
bool MailboxModule::inject_abort(std::span<const std::uint8_t> payload) {
  using namespace ecat::coe;
  if (faults_.abort_code == 0 || payload.size() < sdo::kCommand + 1 ||
      service_of(payload) != Service::SdoRequest ||
      static_cast<sdo::Ccs>(payload[sdo::kCommand] >> 5) == sdo::Ccs::Abort) {
    return false;
  }
  const auto ccs = static_cast<sdo::Ccs>(payload[sdo::kCommand] >> 5);
  const bool initiate = ccs == sdo::Ccs::InitiateDownload || ccs == sdo::Ccs::InitiateUpload;
  const bool addressed = initiate && payload.size() > sdo::kSubindex;
  const std::span<std::uint8_t> slot = queue_.back_slot();
  const std::span<std::uint8_t> reply = slot.subspan(kHeaderSize, sdo::kInitiateSize);
  put_coe_header(reply, Service::SdoRequest);  // an abort travels as an SDO request
  reply[sdo::kCommand] = sdo::kAbort;
  ecat::put_le16(reply, sdo::kIndex, addressed ? ecat::get_le16(payload, sdo::kIndex) : 0);
  reply[sdo::kSubindex] = addressed ? payload[sdo::kSubindex] : 0;
  ecat::put_le32(reply, sdo::kData, faults_.abort_code);
  reply_counter_ = next_counter(reply_counter_);
  Header{static_cast<std::uint16_t>(sdo::kInitiateSize), 0, 0, 0, static_cast<std::uint8_t>(Type::CoE),
         reply_counter_}
      .encode(slot);
  queue_.commit_back(kHeaderSize + sdo::kInitiateSize);
  coe_->reset();  // an abort ends the transfer in progress
  faults_.abort_code = 0;
  return true;
}

// Injected toggle_error: the next upload/download segment response gets the other toggle bit.
void MailboxModule::inject_toggle_error(std::span<std::uint8_t> coe_payload) {
  using namespace ecat::coe;
  if (!faults_.toggle_error || coe_payload.size() <= sdo::kCommand ||
      service_of(coe_payload) != Service::SdoResponse) {
    return;
  }
  const std::uint8_t scs = coe_payload[sdo::kCommand] >> 5;
  if (scs != sdo::kUploadSegmentResponse >> 5 && scs != sdo::kDownloadSegmentResponse >> 5) return;
  coe_payload[sdo::kCommand] ^= sdo::kToggle;
  faults_.toggle_error = false;
}

void MailboxModule::queue_fragments() {
  while (queue_.size() < kReplySlots) {
    const std::span<std::uint8_t> slot = queue_.back_slot();
    const std::size_t n = coe_->next_reply(slot.subspan(kHeaderSize, reply_capacity_ - kHeaderSize));
    if (n == 0) return;
    reply_counter_ = next_counter(reply_counter_);
    Header{static_cast<std::uint16_t>(n), 0, 0, 0, static_cast<std::uint8_t>(Type::CoE),
           reply_counter_}
        .encode(slot);
    queue_.commit_back(kHeaderSize + n);
  }
}

bool MailboxModule::send_next() {
  if (reply_capacity_ < kMinimumWindow) return false;
  // A message lost by an injected fault leaves SM1 free: go on with the next one.
  for (;;) {
    const SmChannel sm1 = context_.pdi.read_sm(1);
    if (!sm1.enabled() || (sm1.status & reg::sm::kMailboxFull) != 0) return false;
    if (duplicate_pending_) return write_duplicate();
    if (emergency_count_ > 0) {
      std::array<std::uint8_t, kHeaderSize + ecat::coe::Emergency::kPayloadSize> message{};
      reply_counter_ = next_counter(reply_counter_);
      Header{ecat::coe::Emergency::kPayloadSize, 0, 0, 0, static_cast<std::uint8_t>(Type::CoE),
             reply_counter_}
          .encode(message);
      emergencies_[emergency_head_].encode(std::span<std::uint8_t>(message).subspan(kHeaderSize));
      emergency_head_ = (emergency_head_ + 1) % kEmergencySlots;
      --emergency_count_;
      if (write_sm1(message)) return true;
      continue;
    }
    if (queue_.empty()) return false;
    const bool written = write_sm1(queue_.front());
    queue_.pop_front();
    if (written) return true;
  }
}

// Injected duplicate_replies: the last message once more, same counter, nothing rotates.
bool MailboxModule::write_duplicate() {
  duplicate_pending_ = false;
  put_sm1(std::span<const std::uint8_t>(sent_.data(), sent_length_));
  return true;
}

// Sends one message: it becomes the one a repeat request resends, then goes to SM1 unless an
// injected fault loses it. Returns whether SM1 got it.
bool MailboxModule::write_sm1(std::span<const std::uint8_t> message) {
  const std::size_t n = std::min(message.size(), reply_capacity_);
  std::copy_n(sent_.begin(), sent_length_, previous_.begin());
  previous_length_ = sent_length_;
  std::copy_n(message.begin(), n, sent_.begin());
  sent_length_ = n;
  if (faults_.lose_replies > 0) {
    --faults_.lose_replies;
    return false;
  }
  put_sm1(message.first(n));
  if (faults_.duplicate_replies > 0) {
    --faults_.duplicate_replies;
    duplicate_pending_ = true;
  }
  return true;
}

// Writes one message into SM1 and pads up to the SM's last byte, which hands it to the master.
void MailboxModule::put_sm1(std::span<const std::uint8_t> message) {
  const std::size_t n = message.size();
  context_.pdi.write(sm1_start_, message);
  std::size_t at = n;
  while (at < sm1_length_) {
    const std::size_t chunk = std::min(zeros_.size(), sm1_length_ - at);
    context_.pdi.write(static_cast<std::uint16_t>(sm1_start_ + at),
                       std::span<const std::uint8_t>(zeros_.data(), chunk));
    at += chunk;
  }
}

// The master toggled SM1 activate bit1: it lost our last reply. Write it again, then answer
// with PDI control bit1 = the request bit (ETG.1000.4 mailbox repeat).
void MailboxModule::service_repeat_request() {
  const SmChannel sm1 = context_.pdi.read_sm(1);
  const bool request = (sm1.activate & reg::sm::kRepeatRequest) != 0;
  const bool ack = (sm1.pdi_control & reg::sm::kRepeatAck) != 0;
  if (request == ack || !sm1.enabled()) return;
  const std::uint16_t pdi_control = sm_register(1, reg::sm::kPdiControl);
  const auto base = static_cast<std::uint8_t>(sm1.pdi_control &
                                              ~(reg::sm::kPdiDeactivate | reg::sm::kRepeatAck));
  // A newer reply still unread in SM1 means the lost one is the one before it: resend that
  // and put the newer one back in front of the queue.
  std::span<const std::uint8_t> resend(sent_.data(), sent_length_);
  if ((sm1.status & reg::sm::kMailboxFull) != 0 && previous_length_ > 0) {
    queue_.push_front(resend);
    resend = std::span<const std::uint8_t>(previous_.data(), previous_length_);
  }
  // Deactivating SM1 from the PDI side clears its buffer state; then it is enabled again.
  context_.pdi.write_u8(pdi_control, static_cast<std::uint8_t>(base | reg::sm::kPdiDeactivate));
  context_.pdi.write_u8(pdi_control, base);
  sm1_start_ = sm1.start;
  sm1_length_ = sm1.length;
  reply_capacity_ = std::min<std::size_t>(sm1_length_, sent_.size());
  if (!resend.empty() && reply_capacity_ >= kMinimumWindow) {
    // Copy first: write_sm1 rotates sent_/previous_.
    std::copy(resend.begin(), resend.end(), resend_.begin());
    write_sm1(std::span<const std::uint8_t>(resend_.data(), resend.size()));
  }
  context_.pdi.write_u8(pdi_control,
                        static_cast<std::uint8_t>(base | (request ? reg::sm::kRepeatAck : 0)));
}

}  // namespace vdrive::firmware::mailbox
