#pragma once
// Where a drive keeps the firmware image it was last given over FoE: its "flash". One file per
// drive, <state_dir>/<product id>-<serial as 8 hex digits>.firmware (named like the parameter
// file of coe/parameter_store.hpp), written to a temporary file, fsync'ed and renamed over the
// old one, so a crash leaves either image whole. When the directory cannot be written the image
// is kept in memory only: it then lasts as long as the process (docs/foe.md).
//
// The image bytes are read into a buffer the caller owns (sized once at construction).
#include <cstdint>
#include <span>
#include <string>

#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::foe {

class FirmwareStore {
public:
  // `state_dir` empty: coe::default_state_dir() ($VDRIVE_STATE_DIR, $XDG_STATE_HOME/vdrive,
  // /var/lib/vdrive).
  FirmwareStore(const profile::ProductProfile& profile, const std::string& state_dir);

  const std::string& path() const { return path_; }

  // Writes `image` atomically. False when the file could not be written (memory-only drive).
  bool save(std::span<const std::uint8_t> image);
  // Reads the stored image into `buffer`; returns its length, 0 when there is none or it does
  // not fit `buffer`.
  std::size_t load(std::span<std::uint8_t> buffer) const;

private:
  std::string dir_, path_, temp_path_;
};

}  // namespace vdrive::firmware::foe
