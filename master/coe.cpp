#include "master/coe.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace vdrive::master {

namespace {
// CoE header: number:9 reserved:3 service:4.
constexpr std::uint8_t kServiceSdoRequest = 2, kServiceSdoResponse = 3, kServiceSdoInfo = 8;
// SDO command specifiers (byte 2 of the CoE message, bits 5-7).
constexpr std::uint8_t kCcsDownloadSegment = 0, kCcsInitiateDownload = 1, kCcsInitiateUpload = 2,
                       kCcsUploadSegment = 3, kAbort = 4;
constexpr std::uint8_t kScsUploadSegment = 0, kScsDownloadSegment = 1, kScsInitiateUpload = 2,
                       kScsInitiateDownload = 3;
constexpr std::uint8_t kCompleteAccess = 0x10, kToggle = 0x10;
constexpr std::size_t kSdoHeader = 10;      // CoE header (2) + command (1) + index (2) + sub (1) + data/size (4)
constexpr std::size_t kSegmentHeader = 3;   // CoE header (2) + command (1)
constexpr std::size_t kMinSegmentData = 7;  // a segment's data field is at least 7 bytes (padded)
// SDO information opcodes.
// A reply's opcode is the request's + 1.
constexpr std::uint8_t kInfoOdListReq = 1, kInfoObjDescReq = 3, kInfoEntryDescReq = 5, kInfoError = 7,
                       kInfoIncomplete = 0x80;

// Bounds against a slave that never stops sending: 64 unrelated CoE messages while waiting for
// an SDO response; 4096 SDO information fragments (an OD list of 65536 indexes needs ~540 in a
// 256-byte mailbox).
constexpr int kMaxUnrelatedReplies = 64, kMaxInfoFragments = 4096;

std::uint16_t u16(std::span<const std::uint8_t> p, std::size_t at) {
  return static_cast<std::uint16_t>(p[at] | (p[at + 1] << 8));
}
std::uint32_t u32(std::span<const std::uint8_t> p, std::size_t at) {
  return static_cast<std::uint32_t>(p[at] | (p[at + 1] << 8) | (p[at + 2] << 16)) | (static_cast<std::uint32_t>(p[at + 3]) << 24);
}
void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void coe_header(std::uint8_t* p, std::uint8_t service) { put16(p, static_cast<std::uint16_t>(service << 12)); }
}  // namespace

SdoAbort::SdoAbort(std::uint16_t index, std::uint8_t subindex, std::uint32_t code)
    : std::runtime_error(fmt::format("SDO abort 0x{:08X} at {:04X}:{:02X}: {}", code, index, subindex, sdo_abort_text(code))),
      index_(index), subindex_(subindex), code_(code) {}

std::string_view sdo_abort_text(std::uint32_t code) {
  switch (code) {
    case 0x05030000: return "Toggle bit not changed";
    case 0x05040000: return "SDO protocol timeout";
    case 0x05040001: return "Client/Server command specifier not valid or unknown";
    case 0x05040005: return "Out of memory";
    case 0x06010000: return "Unsupported access to an object";
    case 0x06010001: return "Attempt to read a write-only object";
    case 0x06010002: return "Attempt to write a read-only object";
    case 0x06010003: return "Subindex cannot be written, SI0 must be 0 for write access";
    case 0x06010004: return "SDO Complete access not supported for objects of variable length";
    case 0x06010005: return "Object length exceeds mailbox size";
    case 0x06010006: return "Object mapped to RxPDO, SDO download blocked";
    case 0x06020000: return "The object does not exist in the object directory";
    case 0x06040041: return "The object can not be mapped into the PDO";
    case 0x06040042: return "The number and length of the objects to be mapped would exceed the PDO length";
    case 0x06040043: return "General parameter incompatibility reason";
    case 0x06040047: return "General internal incompatibility in the device";
    case 0x06060000: return "Access failed due to a hardware error";
    case 0x06070010: return "Data type does not match, length of service parameter does not match";
    case 0x06070012: return "Data type does not match, length of service parameter too high";
    case 0x06070013: return "Data type does not match, length of service parameter too low";
    case 0x06090011: return "Subindex does not exist";
    case 0x06090030: return "Value range of parameter exceeded (only for write access)";
    case 0x06090031: return "Value of parameter written too high";
    case 0x06090032: return "Value of parameter written too low";
    case 0x06090036: return "Maximum value is less than minimum value";
    case 0x08000000: return "General error";
    case 0x08000020: return "Data cannot be transferred or stored to the application";
    case 0x08000021: return "Data cannot be transferred or stored to the application because of local control";
    case 0x08000022: return "Data cannot be transferred or stored to the application because of the present device state";
    case 0x08000023: return "Object dictionary dynamic generation fails or no object dictionary is present";
    default: return "Unknown abort code";
  }
}

std::span<const std::uint8_t> SdoClient::sdo_reply(std::uint16_t index, std::uint8_t subindex) {
  // A slave that keeps sending other CoE services is not answering: give up after a bound.
  for (int others = 0; others < kMaxUnrelatedReplies; ++others) {
    const auto reply = mailbox_.receive(mailbox_type::kCoE);
    if (reply.size() < kSegmentHeader || (reply[1] >> 4) != kServiceSdoResponse) {
      if (reply.size() >= 2 && (reply[1] >> 4) == kServiceSdoRequest && reply.size() >= kSdoHeader &&
          (reply[2] >> 5) == kAbort) {
        throw SdoAbort(index, subindex, u32(reply, 6));  // some slaves send the abort as a request
      }
      continue;  // another CoE service: not our answer
    }
    if ((reply[2] >> 5) == kAbort && reply.size() >= kSdoHeader) throw SdoAbort(index, subindex, u32(reply, 6));
    return reply;
  }
  throw MailboxError(fmt::format("slave 0x{:04X}: no SDO response to {:04X}:{:02X} among {} CoE messages",
                                 mailbox_.config().station, index, subindex, kMaxUnrelatedReplies));
}

std::vector<std::uint8_t> SdoClient::upload(std::uint16_t index, std::uint8_t subindex, bool complete_access) {
  std::array<std::uint8_t, kSdoHeader> req{};
  coe_header(req.data(), kServiceSdoRequest);
  req[2] = static_cast<std::uint8_t>((kCcsInitiateUpload << 5) | (complete_access ? kCompleteAccess : 0));
  put16(&req[3], index);
  req[5] = subindex;
  mailbox_.send(mailbox_type::kCoE, req);

  auto reply = sdo_reply(index, subindex);
  if (reply.size() < kSdoHeader || (reply[2] >> 5) != kScsInitiateUpload || u16(reply, 3) != index ||
      reply[5] != subindex) {
    throw MailboxError(fmt::format("slave 0x{:04X}: unexpected reply to SDO upload {:04X}:{:02X}",
                                   mailbox_.config().station, index, subindex));
  }
  const std::uint8_t cmd = reply[2];
  std::vector<std::uint8_t> data;
  if (cmd & 0x02) {  // expedited: up to 4 bytes in the message
    const std::size_t size = (cmd & 0x01) ? 4 - ((cmd >> 2) & 0x03) : 4;
    data.assign(reply.begin() + 6, reply.begin() + 6 + static_cast<std::ptrdiff_t>(size));
    return data;
  }
  const std::uint32_t total = u32(reply, 6);
  const std::size_t first = std::min<std::size_t>(reply.size() - kSdoHeader, total);
  data.assign(reply.begin() + kSdoHeader, reply.begin() + static_cast<std::ptrdiff_t>(kSdoHeader + first));
  bool toggle = false;
  while (data.size() < total) {  // segmented: ask for the rest, toggling every segment
    std::array<std::uint8_t, kSdoHeader> seg{};
    coe_header(seg.data(), kServiceSdoRequest);
    seg[2] = static_cast<std::uint8_t>((kCcsUploadSegment << 5) | (toggle ? kToggle : 0));
    mailbox_.send(mailbox_type::kCoE, seg);
    const auto part = sdo_reply(index, subindex);
    if ((part[2] >> 5) != kScsUploadSegment) {
      throw MailboxError(fmt::format("slave 0x{:04X}: unexpected reply to upload segment of {:04X}:{:02X}",
                                     mailbox_.config().station, index, subindex));
    }
    if (((part[2] & kToggle) != 0) != toggle) throw SdoAbort(index, subindex, 0x05030000);
    // A minimum-length segment says how many of its 7 bytes are unused; a longer one is all data.
    std::size_t size = part.size() - kSegmentHeader;
    if (part.size() == kSegmentHeader + kMinSegmentData) size = kMinSegmentData - ((part[2] >> 1) & 0x07);
    size = std::min<std::size_t>(size, total - data.size());
    data.insert(data.end(), part.begin() + kSegmentHeader, part.begin() + static_cast<std::ptrdiff_t>(kSegmentHeader + size));
    if (part[2] & 0x01) break;  // last segment
    toggle = !toggle;
  }
  if (data.size() != total) {
    throw MailboxError(fmt::format("slave 0x{:04X}: SDO upload {:04X}:{:02X} ended after {} of {} bytes",
                                   mailbox_.config().station, index, subindex, data.size(), total));
  }
  return data;
}

void SdoClient::download(std::uint16_t index, std::uint8_t subindex, std::span<const std::uint8_t> data,
                         bool complete_access) {
  std::vector<std::uint8_t> msg(mailbox_.max_payload(), 0);
  coe_header(msg.data(), kServiceSdoRequest);
  put16(&msg[3], index);
  msg[5] = subindex;
  std::size_t sent = 0;
  std::size_t length = kSdoHeader;
  const std::uint8_t ca = complete_access ? kCompleteAccess : 0;
  if (data.size() <= 4 && !complete_access) {
    // Expedited: size indicated, n = unused bytes of the 4.
    msg[2] = static_cast<std::uint8_t>((kCcsInitiateDownload << 5) | ((4 - data.size()) << 2) | 0x03);
    std::copy(data.begin(), data.end(), msg.begin() + 6);
    sent = data.size();
  } else {
    msg[2] = static_cast<std::uint8_t>((kCcsInitiateDownload << 5) | ca | 0x01);
    put32(&msg[6], static_cast<std::uint32_t>(data.size()));
    sent = std::min(data.size(), msg.size() - kSdoHeader);
    std::copy(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(sent), msg.begin() + kSdoHeader);
    length = kSdoHeader + sent;
  }
  mailbox_.send(mailbox_type::kCoE, std::span(msg.data(), length));
  const auto reply = sdo_reply(index, subindex);
  if ((reply[2] >> 5) != kScsInitiateDownload || reply.size() < 6 || u16(reply, 3) != index || reply[5] != subindex) {
    throw MailboxError(fmt::format("slave 0x{:04X}: unexpected reply to SDO download {:04X}:{:02X}",
                                   mailbox_.config().station, index, subindex));
  }
  bool toggle = false;
  while (sent < data.size()) {
    const std::size_t room = msg.size() - kSegmentHeader;
    const std::size_t size = std::min(room, data.size() - sent);
    const bool last = sent + size == data.size();
    std::fill(msg.begin(), msg.end(), 0);
    coe_header(msg.data(), kServiceSdoRequest);
    const std::size_t unused = size < kMinSegmentData ? kMinSegmentData - size : 0;
    msg[2] = static_cast<std::uint8_t>((kCcsDownloadSegment << 5) | (toggle ? kToggle : 0) | (unused << 1) | (last ? 1 : 0));
    std::copy(data.begin() + static_cast<std::ptrdiff_t>(sent), data.begin() + static_cast<std::ptrdiff_t>(sent + size),
              msg.begin() + kSegmentHeader);
    mailbox_.send(mailbox_type::kCoE, std::span(msg.data(), kSegmentHeader + size + unused));
    const auto ack = sdo_reply(index, subindex);
    if ((ack[2] >> 5) != kScsDownloadSegment) {
      throw MailboxError(fmt::format("slave 0x{:04X}: unexpected reply to download segment of {:04X}:{:02X}",
                                     mailbox_.config().station, index, subindex));
    }
    if (((ack[2] & kToggle) != 0) != toggle) throw SdoAbort(index, subindex, 0x05030000);
    sent += size;
    toggle = !toggle;
  }
}

std::vector<std::uint8_t> SdoClient::info_request(std::uint8_t opcode, std::span<const std::uint8_t> data,
                                                  std::uint16_t index, std::uint8_t subindex) {
  std::vector<std::uint8_t> req(6 + data.size(), 0);
  coe_header(req.data(), kServiceSdoInfo);
  req[2] = opcode;
  std::copy(data.begin(), data.end(), req.begin() + 6);
  mailbox_.send(mailbox_type::kCoE, req);
  // The reply may come in fragments: "incomplete" set and fragments-left counting down to 0.
  std::vector<std::uint8_t> out;
  for (int messages = 0; messages < kMaxInfoFragments; ++messages) {
    const auto reply = mailbox_.receive(mailbox_type::kCoE);
    if (reply.size() < 6 || (reply[1] >> 4) != kServiceSdoInfo) continue;
    const std::uint8_t op = reply[2] & 0x7F;
    if (op == kInfoError) throw SdoAbort(index, subindex, reply.size() >= 10 ? u32(reply, 6) : 0x08000000);
    if (op != opcode + 1) {
      throw MailboxError(fmt::format("slave 0x{:04X}: SDO info opcode {} in reply to {}", mailbox_.config().station, op, opcode));
    }
    out.insert(out.end(), reply.begin() + 6, reply.end());
    if ((reply[2] & kInfoIncomplete) == 0) return out;
  }
  throw MailboxError(fmt::format("slave 0x{:04X}: SDO information reply not complete after {} messages",
                                 mailbox_.config().station, kMaxInfoFragments));
}

std::vector<std::uint16_t> SdoClient::od_list(std::uint16_t list_type) {
  std::array<std::uint8_t, 2> req{};
  put16(req.data(), list_type);
  const auto data = info_request(kInfoOdListReq, req, 0, 0);
  std::vector<std::uint16_t> indexes;
  // The first fragment starts with the list type, then 2 bytes per index (or per list length).
  for (std::size_t at = 2; at + 1 < data.size(); at += 2) indexes.push_back(u16(data, at));
  return indexes;
}

ObjectDescription SdoClient::object_description(std::uint16_t index) {
  std::array<std::uint8_t, 2> req{};
  put16(req.data(), index);
  const auto data = info_request(kInfoObjDescReq, req, index, 0);
  if (data.size() < 6) throw MailboxError("SDO info: object description too short");
  ObjectDescription d;
  d.index = u16(data, 0);
  d.data_type = u16(data, 2);
  d.max_subindex = data[4];
  d.object_code = data[5];
  d.name.assign(data.begin() + 6, data.end());
  return d;
}

EntryDescription SdoClient::entry_description(std::uint16_t index, std::uint8_t subindex, std::uint8_t value_info) {
  std::array<std::uint8_t, 4> req{};
  put16(req.data(), index);
  req[2] = subindex;
  req[3] = value_info;
  const auto data = info_request(kInfoEntryDescReq, req, index, subindex);
  if (data.size() < 10) throw MailboxError("SDO info: entry description too short");
  EntryDescription d;
  d.index = u16(data, 0);
  d.subindex = data[2];
  d.value_info = data[3];
  d.data_type = u16(data, 4);
  d.bit_length = u16(data, 6);
  d.access = u16(data, 8);
  // Unit type, default, minimum and maximum come before the name when value_info asked for them;
  // the name is what remains when value_info is 0 (the only form this client interprets).
  if (value_info == 0) d.name.assign(data.begin() + 10, data.end());
  return d;
}

}  // namespace vdrive::master
