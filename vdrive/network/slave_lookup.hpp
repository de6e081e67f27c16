#pragma once
// A slave of a served line named as a person names it (ethercat/slave_ref.hpp): by its position,
// or by the station address a master has set in its ESC (register 0x0010).
#include <cstddef>

#include "ethercat/slave_ref.hpp"

namespace vdrive::network {

class Network;

// Its index (0-based); std::invalid_argument names the slaves there are, or the addresses set.
std::size_t find_slave(Network& network, const ecat::SlaveRef& ref);

}  // namespace vdrive::network
