#include "vdrive/firmware/foe/foe_server.hpp"

#include <algorithm>

#include "vdrive/firmware/coe/parameter_store.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::foe {

using ecat::foe::ErrorCode;
using ecat::foe::kHeaderSize;
using ecat::foe::kMailboxOverhead;
using ecat::foe::OpCode;
using ecat::foe::opcode_of;

namespace {
constexpr std::uint16_t kSoftwareVersion = 0x100A;
constexpr std::uint16_t kBusyEntire = 100;  // BUSY reports progress in percent


// The file name of a RRQ/WRQ: the bytes after the header, without trailing NULs (some masters
// send a terminated or padded name).
std::string_view file_name(std::span<const std::uint8_t> request) {
  std::size_t n = request.size() - kHeaderSize;
  while (n > 0 && request[kHeaderSize + n - 1] == 0) --n;
  return std::string_view(reinterpret_cast<const char*>(request.data() + kHeaderSize), n);
}
}  // namespace

FoeServer::FoeServer(FirmwareContext& context, const FoeOptions& options)
    : context_(context),
      store_(context.profile, options.state_dir),
      max_file_bytes_(options.max_file_bytes),
      programming_time_(options.programming_time),
      version_entry_(context.objects.dictionary().find(kSoftwareVersion, 0)),
      factory_version_(context.profile.identity.software_version),
      buffer_(options.max_file_bytes),
      strict_(context.profile.foe_strict_firmware_check) {
  running_length_ = std::min(factory_version_.size(), running_.size());
  std::copy_n(factory_version_.begin(), running_length_, running_.begin());
}

FoeServer::~FoeServer() = default;

mailbox::Outcome FoeServer::on_request(std::span<const std::uint8_t> request,
                                       std::span<std::uint8_t> reply, Nanos now) {
  if (request.size() < kHeaderSize) {
    return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::SizeTooShort);
  }
  switch (opcode_of(request)) {
    case OpCode::WriteRequest: return write_request(request, reply);
    case OpCode::Data: return data(request, reply, now);
    case OpCode::ReadRequest: return error(reply, ErrorCode::NotFound);  // download only (L748)
    case OpCode::Error:
      // The master gave up: the transfer ends, an error is never answered (SSC ecatfoe.c).
      phase_ = Phase::Idle;
      return mailbox::Outcome::none();
    default: return error(reply, ErrorCode::Illegal);
  }
}

mailbox::Outcome FoeServer::write_request(std::span<const std::uint8_t> request,
                                          std::span<std::uint8_t> reply) {
  // A new request replaces any transfer in progress.
  phase_ = Phase::Idle;
  received_ = 0;
  const bool boot = context_.esm.state() == ecat::AlState::Boot;
  if (!strict_) {
    // The manual names no file, password or format (L746-L752): whatever the master sends in
    // Boot is the firmware.
    if (!boot) return error(reply, ErrorCode::BootstrapOnly);
    phase_ = Phase::Writing;
    packet_ = 0;
    return ack(reply, 0);
  }
  const bool firmware = file_name(request).starts_with(kFirmwareNamePrefix);
  if (!firmware) return error(reply, boot ? ErrorCode::NotBootstrap : ErrorCode::AccessDenied);
  if (!boot) return error(reply, ErrorCode::BootstrapOnly);
  if (ecat::foe::field_of(request) != kFirmwarePassword) return error(reply, ErrorCode::NoRights);
  phase_ = Phase::Writing;
  packet_ = 0;
  return ack(reply, 0);
}

mailbox::Outcome FoeServer::data(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply,
                                 Nanos now) {
  const std::uint32_t packet = ecat::foe::field_of(request);
  if (phase_ == Phase::Programming) {
    return packet == packet_ ? programming(reply, now) : error(reply, ErrorCode::PacketNumberWrong);
  }
  if (phase_ == Phase::Done && packet == packet_) return ack(reply, packet);  // our last ACK was lost
  if (phase_ != Phase::Writing) return error(reply, ErrorCode::Illegal);
  if (packet == packet_ && packet_ > 0) return ack(reply, packet);  // repeated: not stored twice
  if (packet != packet_ + 1) return error(reply, ErrorCode::PacketNumberWrong);

  const std::span<const std::uint8_t> bytes = request.subspan(kHeaderSize);
  if (received_ + bytes.size() > buffer_.size()) return error(reply, ErrorCode::DiskFull);
  std::copy(bytes.begin(), bytes.end(), buffer_.begin() + static_cast<std::ptrdiff_t>(received_));
  received_ += bytes.size();
  packet_ = packet;
  const std::size_t full = sm0_length_ > kMailboxOverhead ? sm0_length_ - kMailboxOverhead : 0;
  if (bytes.size() >= full) return ack(reply, packet);
  return last_packet(reply, now);
}

// The file is complete: check it as a firmware image, program it, acknowledge (or report busy).
mailbox::Outcome FoeServer::last_packet(std::span<std::uint8_t> reply, Nanos now) {
  std::array<char, kImageFieldSize> version{};
  std::size_t length = 0;
  const std::span<const std::uint8_t> file(buffer_.data(), received_);
  const ImageCheck check =
      check_image(file, context_.profile.identity.device_name, factory_version_, version, length);
  if (check != ImageCheck::Ok) {
    if (strict_) return error(reply, error_for(check));
    // Another format (the vendor's own file): kept as given. Its version is unknown, so after the
    // restart 100Ah shows the factory text, as it would after a power-on with this image.
    length = std::min(factory_version_.size(), version.size());
    std::copy_n(factory_version_.begin(), length, version.begin());
  }
  last_download_ = {received_, coe::crc32(file.data(), file.size())};
  pending_ = version;
  pending_length_ = length;
  program_image();
  if (programming_time_ > 0) {
    phase_ = Phase::Programming;
    programmed_at_ = now + programming_time_;
    return programming(reply, now);
  }
  phase_ = Phase::Done;
  return ack(reply, packet_);
}

mailbox::Outcome FoeServer::programming(std::span<std::uint8_t> reply, Nanos now) {
  if (now >= programmed_at_) {
    phase_ = Phase::Done;
    return ack(reply, packet_);
  }
  const Nanos elapsed = programming_time_ - (programmed_at_ - now);
  reply[0] = static_cast<std::uint8_t>(OpCode::Busy);
  reply[1] = 0;
  ecat::put_le16(reply, ecat::foe::kBusyDoneAt, static_cast<std::uint16_t>(elapsed * kBusyEntire / programming_time_));
  ecat::put_le16(reply, ecat::foe::kBusyEntireAt, kBusyEntire);
  return mailbox::Outcome::reply(kHeaderSize);
}

// The image goes to flash (the store's file; memory only when that cannot be written).
void FoeServer::program_image() {
  flash_ = pending_;
  flash_length_ = pending_length_;
  store_.save(std::span<const std::uint8_t>(buffer_.data(), received_));
}

void FoeServer::reset() {
  phase_ = Phase::Idle;
  received_ = 0;
}

void FoeServer::restart() {
  if (pending_length_ == 0) return;
  running_ = pending_;
  running_length_ = pending_length_;
  pending_length_ = 0;
  show_version(running_version());
}

void FoeServer::power_on() {
  reset();
  pending_length_ = 0;
  const std::size_t n = store_.load(buffer_);
  std::array<char, kImageFieldSize> version{};
  std::size_t length = 0;
  if (n > 0 && check_image(std::span<const std::uint8_t>(buffer_.data(), n), context_.profile.identity.device_name,
                           factory_version_, version, length) == ImageCheck::Ok) {
    flash_ = version;
    flash_length_ = length;
  }
  if (flash_length_ == 0) return;  // factory firmware: 100Ah keeps its default
  running_ = flash_;
  running_length_ = flash_length_;
  show_version(running_version());
}

void FoeServer::show_version(std::string_view version) {
  if (version_entry_ == nullptr) return;
  const std::span<std::uint8_t> raw = context_.objects.raw(*version_entry_);
  std::fill(raw.begin(), raw.end(), std::uint8_t{0});
  std::copy_n(version.begin(), std::min(version.size(), raw.size()), raw.begin());
}

mailbox::Outcome FoeServer::ack(std::span<std::uint8_t> reply, std::uint32_t packet) {
  ecat::foe::put_header(reply, OpCode::Ack, packet);
  return mailbox::Outcome::reply(kHeaderSize);
}

// An ERR reply ends the transfer (ETG.1000.6: an error aborts the file access).
mailbox::Outcome FoeServer::error(std::span<std::uint8_t> reply, ErrorCode code) {
  phase_ = Phase::Idle;
  received_ = 0;
  ecat::foe::put_header(reply, OpCode::Error, static_cast<std::uint32_t>(code));
  const std::string_view text = error_text(code);
  const std::size_t n = std::min(text.size(), reply.size() - kHeaderSize);
  std::copy_n(text.begin(), n, reply.begin() + kHeaderSize);
  return mailbox::Outcome::reply(kHeaderSize + n);
}

}  // namespace vdrive::firmware::foe
