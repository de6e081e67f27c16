#pragma once
// A signal point resolved to what holds its value: the bytes of an object entry in a slave's
// object store, or a drive's plant and the connection. Reading and writing allocate nothing and
// run on the event loop's thread (the firmware and the plant are not thread-safe).
// Values are integers: an entry's value (sign-extended for signed types), a connection 0 or 1.
#include <cstdint>
#include <string>

#include "vdrive/network/signal_point.hpp"

namespace vdrive::od { struct EntryDesc; }
namespace vdrive::plant { class Plant; }

namespace vdrive::network {

class SignalAccess {
public:
  SignalAccess() = default;
  // Throws std::invalid_argument for an entry that is not an integer (a string, REAL) or longer
  // than 64 bits.
  static SignalAccess entry(std::uint8_t* bytes, const od::EntryDesc& desc);
  static SignalAccess connection(plant::Plant& plant, PlantConnection connection);

  std::int64_t read() const;
  // Throws std::out_of_range (message: the range) when `value` does not fit.
  void check(std::int64_t value) const;
  void write(std::int64_t value) const;  // check()s first
  // The value as the wire ends see it: a connection or a 1-bit entry as 0/1.
  bool is_bit() const { return bits_ == 1; }
  std::uint16_t bits() const { return bits_; }
  bool is_entry() const { return bytes_ != nullptr; }
  std::uint8_t* bytes() const { return bytes_; }
  // "BOOL", "I16", "U32", "connection": for listings.
  std::string type_name() const;

private:
  std::uint8_t* bytes_ = nullptr;
  std::uint16_t bits_ = 1;
  bool signed_ = false;
  plant::Plant* plant_ = nullptr;
  PlantConnection connection_ = PlantConnection::home;
};

}  // namespace vdrive::network
