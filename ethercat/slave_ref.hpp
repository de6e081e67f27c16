#pragma once
// How a person names a slave, in every vdrive and vdrive-master command, file and message: by its
// position in cable order counted from 1 (as the status line, telemetry, scenarios and the web page
// count), or by its station address written in hex ("0x1002"), which the master configures at run
// time (0x1001 for the first slave, the convention of SOEM, IgH and TwinCAT). A slave is printed
// the same way, with both and its product: "slave 2 @0x1002 ds5c1".
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vdrive::ecat {

struct SlaveRef {
  enum class Kind : std::uint8_t { position, address };
  Kind kind = Kind::position;
  std::uint16_t value = 0;  // position (1 = first) or station address
  bool is_address() const { return kind == Kind::address; }
};

inline constexpr std::string_view kSlaveRefForms = "a position (1 = first in cable order) or a station address such as 0x1001";

// Whether `text` is written as a station address ("0x..."), not as a position.
inline bool is_address_text(std::string_view text) {
  return text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
}

// "2" or "0x1002"; anything else (including 0: positions count from 1) is std::invalid_argument
// with a message that says what is accepted.
inline SlaveRef parse_slave_ref(std::string_view text) {
  const bool hex = is_address_text(text);
  const std::string_view digits = hex ? text.substr(2) : text;
  unsigned long v = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v, hex ? 16 : 10);
  if (digits.empty() || ec != std::errc{} || end != digits.data() + digits.size() || v > 0xFFFF)
    throw std::invalid_argument(std::string("'").append(text).append("' names no slave: give ").append(kSlaveRefForms));
  if (!hex && v == 0)
    throw std::invalid_argument("slave 0: positions count from 1 (1 = the first slave in cable order)");
  if (hex && v == 0) throw std::invalid_argument("station address 0x0000 is no slave's (the master sets addresses from 0x0001)");
  return {hex ? SlaveRef::Kind::address : SlaveRef::Kind::position, static_cast<std::uint16_t>(v)};
}

// What is wrong with `text` as a slave reference, or "" when it is one: for option validators.
inline std::string slave_ref_problem(std::string_view text) {
  try {
    (void)parse_slave_ref(text);
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

inline std::string hex_address(std::uint16_t a) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string s = "0x0000";
  for (int i = 0; i < 4; ++i) s[static_cast<std::size_t>(5 - i)] = kDigits[(a >> (4 * i)) & 0xF];
  return s;
}

// The slave's index (0-based) on a line whose slaves have the station addresses `stations`, in
// cable order; std::invalid_argument names the range or the addresses there are.
inline std::size_t slave_index(const SlaveRef& r, std::span<const std::uint16_t> stations) {
  if (!r.is_address()) {
    if (r.value >= 1 && r.value <= stations.size()) return r.value - 1u;
    throw std::invalid_argument(std::string("there is no slave ")
                                    .append(std::to_string(r.value))
                                    .append(": the line has ")
                                    .append(stations.empty() ? std::string("none") : "slaves 1 to " + std::to_string(stations.size())));
  }
  for (std::size_t i = 0; i < stations.size(); ++i)
    if (stations[i] == r.value) return i;
  bool any = false;
  for (const std::uint16_t a : stations) any = any || a != 0;
  if (!stations.empty() && !any)
    throw std::invalid_argument(std::string("no slave has station address ")
                                    .append(hex_address(r.value))
                                    .append(" (no master has set station addresses yet; give the position)"));
  std::string have;
  for (std::size_t i = 0; i < stations.size() && i < 8; ++i) have += (i ? ", " : "") + hex_address(stations[i]);
  if (stations.size() > 8) have += ", ...";
  throw std::invalid_argument(std::string("no slave has station address ")
                                  .append(hex_address(r.value))
                                  .append(have.empty() ? std::string(" (the line has no slaves)") : " (the line has " + have + ")"));
}

// "slave 2 @0x1002 ds5c1"; the address is left out while the master has set none (0), the product
// when it is empty.
inline std::string slave_label(std::size_t index, std::uint16_t station, std::string_view product) {
  std::string s = std::string("slave ").append(std::to_string(index + 1));
  if (station != 0) s.append(" @").append(hex_address(station));
  if (!product.empty()) s.append(" ").append(product);
  return s;
}

}  // namespace vdrive::ecat
