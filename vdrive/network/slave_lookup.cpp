#include "vdrive/network/slave_lookup.hpp"

#include <cstdint>
#include <vector>

#include "ethercat/registers.hpp"
#include "vdrive/network/network.hpp"

namespace vdrive::network {

std::size_t find_slave(Network& network, const ecat::SlaveRef& ref) {
  std::vector<std::uint16_t> stations;
  stations.reserve(network.size());
  for (std::size_t i = 0; i < network.size(); ++i) stations.push_back(network.esc(i).peek_u16(ecat::reg::kStationAddress));
  return ecat::slave_index(ref, stations);
}

}  // namespace vdrive::network
