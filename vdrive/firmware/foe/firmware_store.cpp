#include "vdrive/firmware/foe/firmware_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>

#include "vdrive/firmware/coe/parameter_store.hpp"

namespace vdrive::firmware::foe {

FirmwareStore::FirmwareStore(const profile::ProductProfile& profile, const std::string& state_dir)
    : dir_(state_dir.empty() ? coe::default_state_dir() : state_dir) {
  char name[32];
  std::snprintf(name, sizeof(name), "-%08x.firmware", profile.identity.serial);
  path_ = dir_ + "/" + profile.id + name;
  temp_path_ = path_ + ".tmp";
}

bool FirmwareStore::save(std::span<const std::uint8_t> image) {
  ::mkdir(dir_.c_str(), 0755);  // one level, as a drive has one flash; failure shows at open
  const int fd = ::open(temp_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  bool ok = true;
  for (std::size_t at = 0; ok && at < image.size();) {
    const ssize_t n = ::write(fd, image.data() + at, image.size() - at);
    ok = n > 0;
    if (ok) at += static_cast<std::size_t>(n);
  }
  ok = ok && ::fsync(fd) == 0;
  ok = ::close(fd) == 0 && ok;
  if (!ok || ::rename(temp_path_.c_str(), path_.c_str()) != 0) {
    ::unlink(temp_path_.c_str());
    return false;
  }
  if (const int dir_fd = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
  return true;
}

std::size_t FirmwareStore::load(std::span<std::uint8_t> buffer) const {
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  std::size_t length = 0;
  while (length < buffer.size()) {
    const ssize_t n = ::read(fd, buffer.data() + length, buffer.size() - length);
    if (n <= 0) break;
    length += static_cast<std::size_t>(n);
  }
  std::uint8_t extra = 0;
  const bool longer = ::read(fd, &extra, 1) > 0;
  ::close(fd);
  return longer ? 0 : length;
}

}  // namespace vdrive::firmware::foe
