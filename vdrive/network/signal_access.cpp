#include "vdrive/network/signal_access.hpp"

#include <fmt/core.h>

#include <limits>
#include <stdexcept>

#include "plant/plant.hpp"
#include "vdrive/od/dictionary.hpp"
#include "vdrive/od/entry_value.hpp"

namespace vdrive::network {
namespace {

std::uint32_t input_bit(PlantConnection c) {
  switch (c) {
    case PlantConnection::negative_limit: return plant::input::negative_limit;
    case PlantConnection::positive_limit: return plant::input::positive_limit;
    case PlantConnection::home: return plant::input::home;
    case PlantConnection::probe1: return plant::input::probe1;
    case PlantConnection::probe2: return plant::input::probe2;
    case PlantConnection::brake_release: break;
  }
  return 0;
}

}  // namespace

SignalAccess SignalAccess::entry(std::uint8_t* bytes, const od::EntryDesc& desc) {
  if (od::is_string(desc.type) || desc.type == od::DataType::Real32 || desc.bit_length > 64 || desc.bit_length == 0)
    throw std::invalid_argument(fmt::format("{:04X}h:{:02X}h '{}' is a {}, not an integer a signal can carry",
                                            desc.index, desc.subindex, desc.name, od::short_name(desc.type)));
  SignalAccess a;
  a.bytes_ = bytes;
  a.bits_ = desc.bit_length;
  a.signed_ = od::is_signed(desc.type);
  return a;
}

SignalAccess SignalAccess::connection(plant::Plant& plant, PlantConnection connection) {
  SignalAccess a;
  a.plant_ = &plant;
  a.connection_ = connection;
  return a;
}

std::int64_t SignalAccess::read() const {
  if (plant_ != nullptr) {
    if (connection_ == PlantConnection::brake_release) return plant_->last_command(0).brake_released ? 1 : 0;
    return (plant_->feedback(0).inputs & input_bit(connection_)) != 0 ? 1 : 0;
  }
  std::uint64_t v = 0;
  for (std::uint16_t i = 0; i < (bits_ + 7u) / 8u; ++i) v |= static_cast<std::uint64_t>(bytes_[i]) << (8 * i);
  if (bits_ < 64) {
    v &= (std::uint64_t{1} << bits_) - 1u;
    if (signed_ && (v >> (bits_ - 1)) != 0) v |= ~((std::uint64_t{1} << bits_) - 1u);
  }
  return static_cast<std::int64_t>(v);
}

void SignalAccess::check(std::int64_t value) const {
  const od::IntegerRange range = plant_ != nullptr ? od::IntegerRange{0, 1} : od::integer_range(bits_, signed_);
  const std::int64_t min = range.min, max = range.max;
  if (value < min || value > max) throw std::out_of_range(fmt::format("{} is outside {}..{}", value, min, max));
}

void SignalAccess::write(std::int64_t value) const {
  check(value);
  if (plant_ != nullptr) {
    if (connection_ == PlantConnection::brake_release) {
      plant_->set_brake_control(0, value != 0);
      return;
    }
    const std::uint32_t bits = plant_->external_input(0);
    plant_->set_external_input(0, value != 0 ? bits | input_bit(connection_) : bits & ~input_bit(connection_));
    return;
  }
  const auto u = static_cast<std::uint64_t>(value);
  if (bits_ < 8) {
    const auto mask = static_cast<std::uint8_t>((1u << bits_) - 1u);
    bytes_[0] = static_cast<std::uint8_t>((bytes_[0] & ~mask) | (u & mask));
    return;
  }
  for (std::uint16_t i = 0; i < (bits_ + 7u) / 8u; ++i) bytes_[i] = static_cast<std::uint8_t>(u >> (8 * i));
}

std::string SignalAccess::type_name() const {
  if (plant_ != nullptr) return "connection";
  if (bits_ == 1) return "BOOL";
  return fmt::format("{}{}", signed_ ? 'I' : 'U', bits_);
}

}  // namespace vdrive::network
