#pragma once
// The firmware image a drive with FoE firmware download accepts (docs/foe.md). The manuals give
// no file format (DS1000A-EC: "download procedure: see the master's manual", L746-L752), so this
// is ours, as small as will let a drive tell its own image from a damaged or foreign one:
//
//   bytes 0-7    magic "VDFWIMG1"
//   bytes 8-23   product: the drive's 1008h device name, NUL-padded ("DS1000A-EC")
//   bytes 24-39  version: the 100Ah text the drive reports after the restart, NUL-padded
//   bytes 40-43  payload length (u32, little-endian)
//   bytes 44-47  CRC-32 of the payload (IEEE 802.3, as zlib computes it)
//   bytes 48-    payload (the "program"; its content is not interpreted)
//
// The version must have the shape of the factory 100Ah text: the same length, a digit wherever
// the factory text has a digit and the same character elsewhere (DS1000A-EC "Vn.nn/m.mm",
// L4439), so it fits the object and reads like the product's own.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "ethercat/foe.hpp"

namespace vdrive::firmware::foe {

inline constexpr std::size_t kImageHeaderSize = 48;
inline constexpr std::size_t kImageFieldSize = 16;  // product and version fields
inline constexpr std::string_view kImageMagic = "VDFWIMG1";

enum class ImageCheck : std::uint8_t {
  Ok,
  Damaged,       // too short, length field disagrees, CRC wrong -> 0x800C checksum error
  NotAnImage,    // no magic -> 0x800D
  WrongProduct,  // made for another product -> 0x800D
  BadVersion,    // version not in the product's 100Ah form -> 0x800D
};

// The FoE error a failed check is answered with (Ok -> nothing to report).
ecat::foe::ErrorCode error_for(ImageCheck check);

// Checks `image` for the product whose 1008h is `device_name` and whose factory 100Ah text is
// `factory_version`. On Ok, `version` (capacity kImageFieldSize) receives the new 100Ah text and
// `version_length` its length. Allocates nothing.
ImageCheck check_image(std::span<const std::uint8_t> image, std::string_view device_name,
                       std::string_view factory_version, std::span<char> version,
                       std::size_t& version_length);

// True when `version` has the shape of `factory` (see above).
bool same_version_shape(std::string_view version, std::string_view factory);

// Builds an image (tests, docs, the vdrive-master tool). Allocates.
std::string make_image(std::string_view device_name, std::string_view version,
                       std::span<const std::uint8_t> payload);

}  // namespace vdrive::firmware::foe
