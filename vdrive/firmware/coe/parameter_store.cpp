#include "vdrive/firmware/coe/parameter_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"

namespace vdrive::firmware::coe {

namespace {
constexpr char kMagic[8] = {'V', 'D', 'P', 'A', 'R', 'A', 'M', '1'};
constexpr std::size_t kFileHeader = sizeof(kMagic) + 4;
constexpr std::size_t kEntryHeader = 5;  // index, subindex, size
constexpr std::size_t kCrcSize = 4;

std::size_t value_size(const od::EntryDesc& e) {
  return std::max<std::size_t>(1, (e.bit_length + 7u) / 8u);
}

bool write_all(int fd, const std::uint8_t* data, std::size_t length) {
  while (length > 0) {
    const ssize_t n = ::write(fd, data, length);
    if (n < 0) return false;
    data += n;
    length -= static_cast<std::size_t>(n);
  }
  return true;
}

// Creates `dir` and its parents (best effort; the open of the temp file reports failure).
void make_dirs(const std::string& dir) {
  for (std::size_t at = 1; at <= dir.size(); ++at) {
    if (at == dir.size() || dir[at] == '/') {
      const std::string part = dir.substr(0, at);
      ::mkdir(part.c_str(), 0755);
    }
  }
}
}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t length) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < length; ++i) {
    crc ^= data[i];
    for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string default_state_dir() {
  if (const char* d = std::getenv("VDRIVE_STATE_DIR"); d != nullptr && *d != '\0') return d;
  if (const char* x = std::getenv("XDG_STATE_HOME"); x != nullptr && *x != '\0') {
    return std::string(x) + "/vdrive";
  }
  return "/var/lib/vdrive";
}

ParameterStore::ParameterStore(const profile::ProductProfile& profile, od::ObjectStore& objects,
                               std::string state_dir)
    : objects_(objects), dir_(state_dir.empty() ? default_state_dir() : std::move(state_dir)) {
  const od::Dictionary& dict = objects.dictionary();
  has_store_ = dict.find(kStoreParameters) != nullptr;
  has_restore_ = dict.find(kRestoreDefaults) != nullptr;
  if (!active()) return;
  char name[32];
  std::snprintf(name, sizeof(name), "-%08x.params", profile.identity.serial);
  path_ = dir_ + "/" + profile.id + name;
  temp_path_ = path_ + ".tmp";
  std::size_t bytes = kFileHeader + kCrcSize;
  for (const od::ObjectDesc& o : dict.objects()) {
    for (const od::EntryDesc& e : o.entries) {
      if (persisted(e)) bytes += kEntryHeader + value_size(e);
    }
  }
  buffer_.resize(bytes);
  auto command = [this](const od::EntryDesc& e, std::span<const std::uint8_t> data) {
    if (e.subindex == 0) return od::SdoAbort::Ok;  // the store refuses it (read-only)
    if (data.size() != 4) return od::SdoAbort::LengthMismatch;
    const std::uint32_t value = ecat::get_le32(data, 0);
    if (e.index == kStoreParameters) {
      if (value != kSaveSignature) return od::SdoAbort::CannotTransfer;
      return save() ? od::SdoAbort::Ok : od::SdoAbort::CannotTransfer;
    }
    if (value != kLoadSignature) return od::SdoAbort::CannotTransfer;
    return forget() ? od::SdoAbort::Ok : od::SdoAbort::CannotTransfer;
  };
  if (has_store_) objects.on_write(kStoreParameters, command);
  if (has_restore_) objects.on_write(kRestoreDefaults, command);
  power_on();
}

void ParameterStore::power_on() {
  if (!active()) return;
  load();
  after_download(kStoreParameters, 0);
  after_download(kRestoreDefaults, 0);
}

bool ParameterStore::persisted(const od::EntryDesc& e) const {
  return (e.access & od::access::kWriteAll) != 0 && e.index != kStoreParameters &&
         e.index != kRestoreDefaults;
}

void ParameterStore::after_download(std::uint16_t index, std::uint8_t /*subindex*/) {
  if (index != kStoreParameters && index != kRestoreDefaults) return;
  const od::ObjectDesc* object = objects_.dictionary().find(index);
  if (object == nullptr) return;
  // Bit0 = 1: the drive saves on command (CiA 301); every command subindex reads 1 again.
  for (const od::EntryDesc& e : object->entries) {
    if (e.subindex == 0) continue;
    std::span<std::uint8_t> raw = objects_.raw(e);
    std::fill(raw.begin(), raw.end(), std::uint8_t{0});
    if (!raw.empty()) raw[0] = 1;
  }
}

bool ParameterStore::save() {
  std::size_t at = kFileHeader;
  std::uint32_t count = 0;
  for (const od::ObjectDesc& o : objects_.dictionary().objects()) {
    for (const od::EntryDesc& e : o.entries) {
      if (!persisted(e)) continue;
      const std::span<const std::uint8_t> value = std::as_const(objects_).raw(e);
      const std::size_t n = std::min(value.size(), value_size(e));
      if (at + kEntryHeader + n + kCrcSize > buffer_.size()) return false;
      ecat::put_le16(buffer_, at, e.index);
      buffer_[at + 2] = e.subindex;
      ecat::put_le16(buffer_, at + 3, static_cast<std::uint16_t>(n));
      std::copy_n(value.begin(), n, buffer_.begin() + static_cast<std::ptrdiff_t>(at + kEntryHeader));
      at += kEntryHeader + n;
      ++count;
    }
  }
  std::memcpy(buffer_.data(), kMagic, sizeof(kMagic));
  ecat::put_le32(buffer_, sizeof(kMagic), count);
  ecat::put_le32(buffer_, at, crc32(buffer_.data(), at));
  return write_file(at + kCrcSize);
}

bool ParameterStore::forget() {
  if (buffer_.size() < kFileHeader + kCrcSize) return false;
  std::memcpy(buffer_.data(), kMagic, sizeof(kMagic));
  ecat::put_le32(buffer_, sizeof(kMagic), 0);
  ecat::put_le32(buffer_, kFileHeader, crc32(buffer_.data(), kFileHeader));
  return write_file(kFileHeader + kCrcSize);
}

// Temp file, fsync, rename over the target, fsync the directory: the target is always whole.
bool ParameterStore::write_file(std::size_t length) {
  make_dirs(dir_);
  const int fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  bool ok = write_all(fd, buffer_.data(), length) && ::fsync(fd) == 0;
  ok = ::close(fd) == 0 && ok;
  if (!ok || ::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    ::unlink(temp_path_.c_str());
    return false;
  }
  const int dir_fd = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
  return true;
}

bool ParameterStore::load() {
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  std::size_t length = 0;
  while (length < buffer_.size()) {
    const ssize_t n = ::read(fd, buffer_.data() + length, buffer_.size() - length);
    if (n <= 0) break;
    length += static_cast<std::size_t>(n);
  }
  std::uint8_t extra = 0;
  const bool longer = ::read(fd, &extra, 1) > 0;
  ::close(fd);
  if (longer || length < kFileHeader + kCrcSize) return false;
  if (std::memcmp(buffer_.data(), kMagic, sizeof(kMagic)) != 0) return false;
  const std::size_t body = length - kCrcSize;
  if (ecat::get_le32(buffer_, body) != crc32(buffer_.data(), body)) return false;
  const std::uint32_t count = ecat::get_le32(buffer_, sizeof(kMagic));
  std::size_t at = kFileHeader;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (at + kEntryHeader > body) return false;
    const std::uint16_t index = ecat::get_le16(buffer_, at);
    const std::uint8_t sub = buffer_[at + 2];
    const std::size_t n = ecat::get_le16(buffer_, at + 3);
    at += kEntryHeader;
    if (at + n > body) return false;
    // Entries the dictionary no longer has, or whose size changed, keep their defaults.
    if (const od::EntryDesc* e = objects_.dictionary().find(index, sub);
        e != nullptr && persisted(*e)) {
      std::span<std::uint8_t> raw = objects_.raw(*e);
      if (raw.size() == n) std::copy_n(buffer_.begin() + static_cast<std::ptrdiff_t>(at), n, raw.begin());
    }
    at += n;
  }
  return true;
}

}  // namespace vdrive::firmware::coe
