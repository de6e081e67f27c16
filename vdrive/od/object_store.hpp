#pragma once
// The values of one slave's object dictionary, with CoE access rules: state-dependent access,
// range checks, length checks, and hooks the firmware installs for objects with side effects
// (PDO mapping, 6040h, store/restore ...). One flat byte array; reads, writes and PDO copies
// allocate nothing.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "ethercat/al_state.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/sdo_abort.hpp"

namespace vdrive::od {

class ObjectStore {
public:
  explicit ObjectStore(const Dictionary& dictionary);   // values = defaults

  const Dictionary& dictionary() const { return dict_; }

  // SDO access to one entry. `out` receives the value's bytes (little-endian); `written` its size.
  SdoAbort read(std::uint16_t index, std::uint8_t subindex, std::span<std::uint8_t> out,
                std::size_t& written, ecat::AlState state) const;
  SdoAbort write(std::uint16_t index, std::uint8_t subindex, std::span<const std::uint8_t> data,
                 ecat::AlState state);

  // Firmware-side access: no state or access checks (the drive updates its own ro objects).
  std::span<std::uint8_t> raw(const EntryDesc& entry) {
    return {values_.data() + entry.value_offset, entry.value_bytes};
  }
  std::span<const std::uint8_t> raw(const EntryDesc& entry) const {
    return {values_.data() + entry.value_offset, entry.value_bytes};
  }

  // Called before a checked write is stored; return non-Ok to refuse it with that abort code.
  // Installed by the firmware at start-up (allocation allowed then, never per access).
  using WriteHook = std::function<SdoAbort(const EntryDesc&, std::span<const std::uint8_t>)>;
  void on_write(std::uint16_t index, WriteHook hook);

  // Back to defaults (power-on, 1011h restore).
  void reset_to_defaults();

private:
  const Dictionary& dict_;
  std::vector<std::uint8_t> values_;
  std::vector<std::pair<std::uint16_t, WriteHook>> hooks_;   // sorted by index
};

}  // namespace vdrive::od
