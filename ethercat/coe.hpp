#pragma once
// CoE on the wire (ETG.1000.6 5.6): the 2-byte CoE header, SDO command bytes and the SDO
// Information header. Offsets are into the mailbox payload (after the 6-byte mailbox header);
// multi-byte fields are little-endian (ethercat/little_endian.hpp).
#include <cstddef>
#include <cstdint>
#include <span>

namespace vdrive::ecat::coe {

// CoE header: bits 8:0 number (0), bits 15:12 service.
enum class Service : std::uint8_t {
  Emergency = 1,
  SdoRequest = 2,
  SdoResponse = 3,
  TxPdo = 4,
  RxPdo = 5,
  TxPdoRemoteRequest = 6,
  RxPdoRemoteRequest = 7,
  SdoInformation = 8,
};
inline constexpr std::size_t kCoeHeaderSize = 2;

constexpr Service service_of(std::span<const std::uint8_t> payload) {
  return static_cast<Service>(payload[1] >> 4);
}
constexpr void put_coe_header(std::span<std::uint8_t> out, Service service) {
  out[0] = 0;
  out[1] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(service) << 4);
}

// SDO frame: CoE header, command, index (2), subindex, then 4 bytes of data or size.
namespace sdo {
inline constexpr std::size_t kCommand = 2, kIndex = 3, kSubindex = 5, kData = 6;
inline constexpr std::size_t kInitiateSize = 10;   // up to and including the 4 data bytes
inline constexpr std::size_t kNormalData = 10;     // normal transfer: data after the size
inline constexpr std::size_t kSegmentData = 3;     // segment: data right after the command
inline constexpr std::size_t kMinSegmentData = 7;  // a segment frame is never shorter

// Client command specifiers (bits 7:5 of the request's command byte).
enum class Ccs : std::uint8_t {
  DownloadSegment = 0,
  InitiateDownload = 1,
  InitiateUpload = 2,
  UploadSegment = 3,
  Abort = 4,
};
inline constexpr int kCommandSpecifierShift = 5;
constexpr Ccs ccs_of(std::uint8_t command) { return static_cast<Ccs>(command >> kCommandSpecifierShift); }
inline constexpr std::uint8_t kSizeIndicator = 0x01;   // initiate: size given
inline constexpr std::uint8_t kExpedited = 0x02;       // initiate: data in the 4 bytes
inline constexpr std::uint8_t kCompleteAccess = 0x10;  // initiate: whole object
inline constexpr std::uint8_t kToggle = 0x10;          // segments
inline constexpr std::uint8_t kLastSegment = 0x01;     // segments: no more follow

// Server command bytes.
inline constexpr std::uint8_t kDownloadResponse = 0x60;          // scs 3
inline constexpr std::uint8_t kUploadResponse = 0x40;            // scs 2
inline constexpr std::uint8_t kDownloadSegmentResponse = 0x20;   // scs 1
inline constexpr std::uint8_t kUploadSegmentResponse = 0x00;     // scs 0
inline constexpr std::uint8_t kAbort = 0x80;                     // cs 4
}  // namespace sdo

// SDO Information (ETG.1000.6 5.6.3): CoE header, opcode (bit 7: more fragments follow), reserved,
// fragments left (2 bytes), then the service data.
namespace info {
enum class Opcode : std::uint8_t {
  GetOdListRequest = 1,
  GetOdListResponse = 2,
  GetObjectDescriptionRequest = 3,
  GetObjectDescriptionResponse = 4,
  GetEntryDescriptionRequest = 5,
  GetEntryDescriptionResponse = 6,
  ErrorRequest = 7,
};
inline constexpr std::uint8_t kIncomplete = 0x80;
inline constexpr std::size_t kHeaderSize = 6;   // CoE header, opcode, reserved, fragments left
// Entry description request: value info bits.
inline constexpr std::uint8_t kUnitType = 0x08, kDefault = 0x10, kMinimum = 0x20, kMaximum = 0x40;
}  // namespace info

}  // namespace vdrive::ecat::coe
