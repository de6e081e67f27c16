#pragma once
// Store/restore parameters (CiA 301 1010h/1011h) for products that have them (A6B: 1010h only,
// L8784-L8904; neither Xinje drive has them). Writing "save" (65766173h) to 1010h:01 writes every
// writable object of the drive to its file; writing "load" (64616F6Ch) to 1011h:01 makes the next
// power-on start from defaults. Any other value is refused with 08000020h (cannot be stored),
// which the A6B lists as supported (L4411-L4552). After the command the subindex reads 1 again
// ("saves on command", A6B L8784-L8904).
//
// The file is per drive: <state_dir>/<product id>-<serial as 8 hex digits>.params. It is written
// to a temporary file, fsync'ed, then renamed over the old one and the directory fsync'ed, so a
// crash at any point leaves either the old or the new file, never a torn one. It is loaded when
// the drive powers on (construction). Format: "VDPARAM1", entry count (u32), then per entry index
// (u16), subindex (u8), size (u16), value bytes, then a CRC-32 of everything before it; a file
// that fails any check is ignored (the drive starts from defaults).
//
// The file I/O runs inside the SDO download (the A6B takes up to 10 s and answers no other SDO
// meanwhile, L8860-L8870); it uses a buffer sized at construction and POSIX calls, no allocation.
#include <cstdint>
#include <string>
#include <vector>

#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::coe {

inline constexpr std::uint32_t kSaveSignature = 0x65766173;  // "save"
inline constexpr std::uint32_t kLoadSignature = 0x64616F6C;  // "load"
inline constexpr std::uint16_t kStoreParameters = 0x1010;
inline constexpr std::uint16_t kRestoreDefaults = 0x1011;

// $VDRIVE_STATE_DIR, else $XDG_STATE_HOME/vdrive, else /var/lib/vdrive.
std::string default_state_dir();

class ParameterStore {
public:
  // Loads the drive's file into `objects` if there is a valid one, and installs the 1010h/1011h
  // write hooks when the dictionary has those objects.
  ParameterStore(const profile::ProductProfile& profile, od::ObjectStore& objects,
                 std::string state_dir);

  // Power-on (after the store was reset to defaults): load the file, commands read 1.
  void power_on();

  bool active() const { return has_store_ || has_restore_; }
  const std::string& path() const { return path_; }

  // Writes the current values (temp file + fsync + rename). False on any I/O failure.
  bool save();
  // Next power-on starts from defaults: the file is replaced by an empty one (atomically too).
  bool forget();
  // Loads the file into the store; false if there is none or it is invalid.
  bool load();
  // After a successful SDO write to 1010h/1011h: the command subindex reads 1 again.
  void after_download(std::uint16_t index, std::uint8_t subindex);

private:
  bool persisted(const od::EntryDesc& entry) const;
  bool write_file(std::size_t length);

  od::ObjectStore& objects_;
  std::string dir_, path_, temp_path_;
  std::vector<std::uint8_t> buffer_;
  bool has_store_ = false, has_restore_ = false;
};

// CRC-32 (IEEE 802.3, reflected, as zlib computes it).
std::uint32_t crc32(const std::uint8_t* data, std::size_t length);

}  // namespace vdrive::firmware::coe
