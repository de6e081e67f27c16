#include "vdrive/firmware/coe/sdo_server.hpp"

#include <algorithm>

#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"

namespace vdrive::firmware::coe {

using ecat::coe::put_coe_header;
using ecat::coe::Service;
namespace sdo = ecat::coe::sdo;

namespace {
constexpr std::uint8_t kCoeCompleteAccess = 0x20;  // SII General CoE details bit5

std::size_t entry_bytes(const od::EntryDesc& e) {
  return std::max<std::size_t>(1, (e.bit_length + 7u) / 8u);
}

// Bytes of the largest object as complete access sends it (subindex 0 as 16 bits).
std::size_t largest_object(const od::Dictionary& dict) {
  std::size_t largest = 4;
  for (const od::ObjectDesc& o : dict.objects()) {
    std::size_t bytes = 1;  // subindex 0 widened to 16 bits
    for (const od::EntryDesc& e : o.entries) bytes += entry_bytes(e);
    largest = std::max(largest, bytes);
  }
  return largest;
}
}  // namespace

od::SdoAbort complete_access_refusal(const profile::ProductProfile& profile) {
  return static_cast<od::SdoAbort>(profile.complete_access_abort);
}

SdoServer::SdoServer(const profile::ProductProfile& profile, od::ObjectStore& objects,
                     const AlStateMachine& esm, ParameterStore* parameters, SdoAbortRecord* aborts)
    : profile_(profile),
      objects_(objects),
      esm_(esm),
      parameters_(parameters),
      aborts_(aborts),
      complete_access_((profile.coe_details & kCoeCompleteAccess) != 0),
      value_(largest_object(objects.dictionary())) {}

mailbox::Outcome SdoServer::on_request(std::span<const std::uint8_t> request,
                                       std::span<std::uint8_t> reply) {
  if (request.size() < sdo::kSegmentData) {
    return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::SizeTooShort);
  }
  const auto ccs = static_cast<sdo::Ccs>(request[sdo::kCommand] >> 5);
  const bool initiate = ccs == sdo::Ccs::InitiateDownload || ccs == sdo::Ccs::InitiateUpload;
  if (initiate && request.size() < sdo::kInitiateSize) {
    return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::SizeTooShort);
  }
  put_coe_header(reply, Service::SdoResponse);
  switch (ccs) {
    case sdo::Ccs::InitiateUpload: return mailbox::Outcome::reply(initiate_upload(request, reply));
    case sdo::Ccs::UploadSegment: return mailbox::Outcome::reply(upload_segment(request, reply));
    case sdo::Ccs::InitiateDownload:
      return mailbox::Outcome::reply(initiate_download(request, reply));
    case sdo::Ccs::DownloadSegment:
      return mailbox::Outcome::reply(download_segment(request, reply));
    case sdo::Ccs::Abort:
      transfer_ = Transfer::None;  // the master gave up: no answer
      return mailbox::Outcome::none();
  }
  const std::uint16_t index = request.size() >= 6 ? ecat::get_le16(request, sdo::kIndex) : 0;
  const std::uint8_t sub = request.size() >= 6 ? request[sdo::kSubindex] : 0;
  transfer_ = Transfer::None;
  return mailbox::Outcome::reply(abort(reply, index, sub, od::SdoAbort::UnknownCommand));
}

std::size_t SdoServer::abort(std::span<std::uint8_t> reply, std::uint16_t index,
                             std::uint8_t subindex, od::SdoAbort code) {
  put_coe_header(reply, Service::SdoRequest);  // an abort travels as an SDO request (ETG.1000.6)
  reply[sdo::kCommand] = sdo::kAbort;
  ecat::put_le16(reply, sdo::kIndex, index);
  reply[sdo::kSubindex] = subindex;
  ecat::put_le32(reply, sdo::kData, static_cast<std::uint32_t>(code));
  if (aborts_ != nullptr) *aborts_ = {aborts_->count + 1, index, subindex, static_cast<std::uint32_t>(code)};
  return sdo::kInitiateSize;
}

std::size_t SdoServer::download_response(std::span<std::uint8_t> reply, std::uint16_t index,
                                         std::uint8_t subindex) {
  reply[sdo::kCommand] = sdo::kDownloadResponse;
  ecat::put_le16(reply, sdo::kIndex, index);
  reply[sdo::kSubindex] = subindex;
  ecat::put_le32(reply, sdo::kData, 0);
  return sdo::kInitiateSize;
}

od::SdoAbort SdoServer::read_object(std::uint16_t index, std::uint8_t subindex, bool complete,
                                    std::size_t& size) {
  const ecat::AlState state = esm_.state();
  if (!complete) return objects_.read(index, subindex, value_, size, state);
  const od::ObjectDesc* object = objects_.dictionary().find(index);
  if (object == nullptr) return od::SdoAbort::NoSuchObject;
  if (subindex > 1) return od::SdoAbort::UnsupportedAccess;
  std::size_t n = 0;
  std::uint8_t count = object->max_subindex();
  if (object->code != od::ObjectCode::Var) {
    const od::SdoAbort r = objects_.read(index, 0, value_, n, state);
    if (r != od::SdoAbort::Ok) return r;
    count = std::min(value_[0], object->max_subindex());
  }
  std::size_t at = 0;
  if (subindex == 0) {
    value_[0] = count;
    value_[1] = 0;  // subindex 0 padded to 16 bits (ETG.1000.6 complete access)
    at = 2;
  }
  for (const od::EntryDesc& e : object->entries) {
    if (e.subindex == 0 || e.subindex > count) continue;
    const od::SdoAbort r = objects_.read(
        index, e.subindex, std::span<std::uint8_t>(value_).subspan(at), n, state);
    if (r != od::SdoAbort::Ok) return r;
    at += n;
  }
  size = at;
  return od::SdoAbort::Ok;
}

od::SdoAbort SdoServer::write_object(std::uint16_t index, std::uint8_t subindex, bool complete,
                                     std::span<const std::uint8_t> data) {
  const ecat::AlState state = esm_.state();
  od::SdoAbort result = od::SdoAbort::Ok;
  if (!complete) {
    result = objects_.write(index, subindex, data, state);
  } else {
    const od::ObjectDesc* object = objects_.dictionary().find(index);
    if (object == nullptr) return od::SdoAbort::NoSuchObject;
    if (subindex > 1) return od::SdoAbort::UnsupportedAccess;
    std::size_t at = 0;
    std::uint8_t count = object->max_subindex();
    if (subindex == 0) {
      if (data.size() < 2) return od::SdoAbort::LengthTooLow;
      count = data[0];
      at = 2;
      // Like a master remapping by hand: count to 0, the entries, then the new count.
      const std::uint8_t zero = 0;
      result = objects_.write(index, 0, std::span<const std::uint8_t>(&zero, 1), state);
      if (result != od::SdoAbort::Ok) return result;
    }
    for (const od::EntryDesc& e : object->entries) {
      if (e.subindex == 0 || e.subindex > count) continue;
      const std::size_t n = entry_bytes(e);
      if (at + n > data.size()) return od::SdoAbort::LengthTooLow;
      result = objects_.write(index, e.subindex, data.subspan(at, n), state);
      if (result != od::SdoAbort::Ok) return result;
      at += n;
    }
    if (at != data.size()) return od::SdoAbort::LengthTooHigh;
    if (subindex == 0) {
      result = objects_.write(index, 0, std::span<const std::uint8_t>(&count, 1), state);
    }
  }
  if (result == od::SdoAbort::Ok && parameters_ != nullptr) {
    parameters_->after_download(index, subindex);
  }
  return result;
}

std::size_t SdoServer::initiate_upload(std::span<const std::uint8_t> request,
                                       std::span<std::uint8_t> reply) {
  transfer_ = Transfer::None;
  const std::uint16_t index = ecat::get_le16(request, sdo::kIndex);
  const std::uint8_t sub = request[sdo::kSubindex];
  const bool complete = (request[sdo::kCommand] & sdo::kCompleteAccess) != 0;
  if (complete && !complete_access_) return abort(reply, index, sub, complete_access_refusal(profile_));
  std::size_t size = 0;
  const od::SdoAbort r = read_object(index, sub, complete, size);
  if (r != od::SdoAbort::Ok) return abort(reply, index, sub, r);
  ecat::put_le16(reply, sdo::kIndex, index);
  reply[sdo::kSubindex] = sub;
  if (size <= 4 && !complete) {
    reply[sdo::kCommand] = static_cast<std::uint8_t>(sdo::kUploadResponse | sdo::kExpedited |
                                                     sdo::kSizeIndicator | ((4 - size) << 2));
    ecat::put_le32(reply, sdo::kData, 0);
    std::copy_n(value_.begin(), size, reply.begin() + sdo::kData);
    return sdo::kInitiateSize;
  }
  reply[sdo::kCommand] = static_cast<std::uint8_t>(sdo::kUploadResponse | sdo::kSizeIndicator |
                                                   (complete ? sdo::kCompleteAccess : 0));
  ecat::put_le32(reply, sdo::kData, static_cast<std::uint32_t>(size));
  const std::size_t chunk = std::min(size, reply.size() - sdo::kNormalData);
  std::copy_n(value_.begin(), chunk, reply.begin() + sdo::kNormalData);
  if (chunk < size) {  // the rest follows in upload segments
    transfer_ = Transfer::Upload;
    index_ = index;
    subindex_ = sub;
    complete_ = complete;
    toggle_ = false;
    size_ = size;
    offset_ = chunk;
  }
  return sdo::kNormalData + chunk;
}

std::size_t SdoServer::upload_segment(std::span<const std::uint8_t> request,
                                      std::span<std::uint8_t> reply) {
  if (transfer_ != Transfer::Upload) return abort(reply, 0, 0, od::SdoAbort::UnknownCommand);
  const bool toggle = (request[sdo::kCommand] & sdo::kToggle) != 0;
  if (toggle != toggle_) {
    transfer_ = Transfer::None;
    return abort(reply, index_, subindex_, od::SdoAbort::ToggleBit);
  }
  const std::size_t seg = std::min(size_ - offset_, reply.size() - sdo::kSegmentData);
  const bool last = offset_ + seg == size_;
  std::uint8_t command = sdo::kUploadSegmentResponse | (toggle ? sdo::kToggle : 0);
  if (last) command |= sdo::kLastSegment;
  std::copy_n(value_.begin() + static_cast<std::ptrdiff_t>(offset_), seg,
              reply.begin() + sdo::kSegmentData);
  std::size_t length = sdo::kSegmentData + seg;
  if (seg < sdo::kMinSegmentData) {  // a segment frame is padded to 7 data bytes; n = unused
    command |= static_cast<std::uint8_t>((sdo::kMinSegmentData - seg) << 1);
    std::fill(reply.begin() + static_cast<std::ptrdiff_t>(length),
              reply.begin() + sdo::kInitiateSize, std::uint8_t{0});
    length = sdo::kInitiateSize;
  }
  reply[sdo::kCommand] = command;
  offset_ += seg;
  toggle_ = !toggle_;
  if (last) transfer_ = Transfer::None;
  return length;
}

std::size_t SdoServer::initiate_download(std::span<const std::uint8_t> request,
                                         std::span<std::uint8_t> reply) {
  transfer_ = Transfer::None;
  const std::uint8_t command = request[sdo::kCommand];
  const std::uint16_t index = ecat::get_le16(request, sdo::kIndex);
  const std::uint8_t sub = request[sdo::kSubindex];
  const bool complete = (command & sdo::kCompleteAccess) != 0;
  if (complete && !complete_access_) return abort(reply, index, sub, complete_access_refusal(profile_));
  if (command & sdo::kExpedited) {
    std::size_t size = 4;
    if (command & sdo::kSizeIndicator) {
      size = 4 - ((command >> 2) & 0x03);
    } else if (const od::EntryDesc* e = objects_.dictionary().find(index, sub); e != nullptr) {
      size = std::min<std::size_t>(4, entry_bytes(*e));  // no size given: the entry's own
    }
    const od::SdoAbort r = write_object(index, sub, complete, request.subspan(sdo::kData, size));
    if (r != od::SdoAbort::Ok) return abort(reply, index, sub, r);
    return download_response(reply, index, sub);
  }
  const std::size_t size = ecat::get_le32(request, sdo::kData);
  const std::size_t here = std::min(size, request.size() - sdo::kNormalData);
  if (here == size) {
    const od::SdoAbort r = write_object(index, sub, complete, request.subspan(sdo::kNormalData, size));
    if (r != od::SdoAbort::Ok) return abort(reply, index, sub, r);
    return download_response(reply, index, sub);
  }
  // The rest follows in download segments; it must fit the largest object of this drive.
  if (size > value_.size()) return abort(reply, index, sub, od::SdoAbort::LengthMismatch);
  if (objects_.dictionary().find(index) == nullptr) {
    return abort(reply, index, sub, od::SdoAbort::NoSuchObject);
  }
  if (!complete && objects_.dictionary().find(index, sub) == nullptr) {
    return abort(reply, index, sub, od::SdoAbort::NoSuchSubindex);
  }
  std::copy_n(request.begin() + sdo::kNormalData, here, value_.begin());
  transfer_ = Transfer::Download;
  index_ = index;
  subindex_ = sub;
  complete_ = complete;
  toggle_ = false;
  size_ = size;
  offset_ = here;
  return download_response(reply, index, sub);
}

std::size_t SdoServer::download_segment(std::span<const std::uint8_t> request,
                                        std::span<std::uint8_t> reply) {
  if (transfer_ != Transfer::Download) return abort(reply, 0, 0, od::SdoAbort::UnknownCommand);
  const std::uint8_t command = request[sdo::kCommand];
  const bool toggle = (command & sdo::kToggle) != 0;
  if (toggle != toggle_) {
    transfer_ = Transfer::None;
    return abort(reply, index_, subindex_, od::SdoAbort::ToggleBit);
  }
  // A segment of fewer than 7 bytes is padded to 7 and says how many are unused.
  std::size_t seg = request.size() - sdo::kSegmentData;
  if (request.size() <= sdo::kInitiateSize) {
    const std::size_t unused = (command >> 1) & 0x07;
    seg = std::min(seg, sdo::kMinSegmentData - unused);
  }
  if (offset_ + seg > size_) {
    transfer_ = Transfer::None;
    return abort(reply, index_, subindex_, od::SdoAbort::LengthMismatch);
  }
  std::copy_n(request.begin() + sdo::kSegmentData, seg,
              value_.begin() + static_cast<std::ptrdiff_t>(offset_));
  offset_ += seg;
  toggle_ = !toggle_;
  if (command & sdo::kLastSegment) {
    transfer_ = Transfer::None;
    if (offset_ != size_) return abort(reply, index_, subindex_, od::SdoAbort::LengthMismatch);
    const od::SdoAbort r = write_object(index_, subindex_, complete_,
                                        std::span<const std::uint8_t>(value_.data(), size_));
    if (r != od::SdoAbort::Ok) return abort(reply, index_, subindex_, r);
  }
  reply[sdo::kCommand] = static_cast<std::uint8_t>(sdo::kDownloadSegmentResponse |
                                                   (toggle ? sdo::kToggle : 0));
  std::fill(reply.begin() + sdo::kIndex, reply.begin() + sdo::kInitiateSize, std::uint8_t{0});
  return sdo::kInitiateSize;
}

}  // namespace vdrive::firmware::coe
