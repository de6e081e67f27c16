#include "vdrive/firmware/foe/firmware_image.hpp"

#include <algorithm>
#include <cctype>

#include "ethercat/little_endian.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"

namespace vdrive::firmware::foe {

using ecat::foe::ErrorCode;

namespace {
constexpr std::size_t kProductAt = 8, kVersionAt = 24, kLengthAt = 40, kCrcAt = 44;

// A NUL-padded text field: the characters up to the first NUL.
std::string_view field(std::span<const std::uint8_t> image, std::size_t at) {
  const char* p = reinterpret_cast<const char*>(image.data() + at);
  std::size_t n = 0;
  while (n < kImageFieldSize && p[n] != '\0') ++n;
  return std::string_view(p, n);
}
}  // namespace

ErrorCode error_for(ImageCheck check) {
  return check == ImageCheck::Damaged ? ErrorCode::ChecksumError : ErrorCode::FirmwareDoesNotFit;
}

bool same_version_shape(std::string_view version, std::string_view factory) {
  if (version.size() != factory.size() || version.empty()) return false;
  for (std::size_t i = 0; i < version.size(); ++i) {
    const bool digit = std::isdigit(static_cast<unsigned char>(factory[i])) != 0;
    if (digit ? std::isdigit(static_cast<unsigned char>(version[i])) == 0 : version[i] != factory[i]) {
      return false;
    }
  }
  return true;
}

ImageCheck check_image(std::span<const std::uint8_t> image, std::string_view device_name,
                       std::string_view factory_version, std::span<char> version,
                       std::size_t& version_length) {
  version_length = 0;
  if (image.size() < kImageMagic.size() ||
      !std::equal(kImageMagic.begin(), kImageMagic.end(), image.begin())) {
    return ImageCheck::NotAnImage;
  }
  if (image.size() < kImageHeaderSize) return ImageCheck::Damaged;
  const std::uint32_t length = ecat::get_le32(image, kLengthAt);
  if (length != image.size() - kImageHeaderSize) return ImageCheck::Damaged;
  const std::span<const std::uint8_t> payload = image.subspan(kImageHeaderSize);
  if (coe::crc32(payload.data(), payload.size()) != ecat::get_le32(image, kCrcAt)) return ImageCheck::Damaged;
  if (field(image, kProductAt) != device_name) return ImageCheck::WrongProduct;
  const std::string_view v = field(image, kVersionAt);
  if (!same_version_shape(v, factory_version) || v.size() > version.size()) return ImageCheck::BadVersion;
  std::copy(v.begin(), v.end(), version.begin());
  version_length = v.size();
  return ImageCheck::Ok;
}

std::string make_image(std::string_view device_name, std::string_view version,
                       std::span<const std::uint8_t> payload) {
  std::string image(kImageHeaderSize, '\0');
  std::copy(kImageMagic.begin(), kImageMagic.end(), image.begin());
  std::copy_n(device_name.begin(), std::min(device_name.size(), kImageFieldSize), image.begin() + kProductAt);
  std::copy_n(version.begin(), std::min(version.size(), kImageFieldSize), image.begin() + kVersionAt);
  auto* bytes = reinterpret_cast<std::uint8_t*>(image.data());
  ecat::put_le32(std::span<std::uint8_t>(bytes, image.size()), kLengthAt, static_cast<std::uint32_t>(payload.size()));
  ecat::put_le32(std::span<std::uint8_t>(bytes, image.size()), kCrcAt, coe::crc32(payload.data(), payload.size()));
  image.append(reinterpret_cast<const char*>(payload.data()), payload.size());
  return image;
}

}  // namespace vdrive::firmware::foe
