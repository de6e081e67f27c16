#pragma once
// Process data configuration (ETG.1000.6 / ETG.2000 practice, as SOEM's ec_config_map does):
//
//  1. per slave, the assigned PDOs of SM2 (outputs, 1C12h) and SM3 (inputs, 1C13h) and their
//     mapping (16xxh/1Axxh, entries index<<16 | sub<<8 | bit length) read with SDO uploads, or
//     taken from the SII RxPDO/TxPDO categories when the slave has no CoE, does not answer, or
//     assigns no PDO at all (SOEM's rule);
//  2. sizes rounded up to whole bytes; SM2/SM3 written with the SII start address and control
//     byte and the computed length (disabled when nothing is mapped);
//  3. a logical process image: all slaves' outputs first, then all inputs, from logical address
//     0; FMMU0 maps a slave's outputs (write), FMMU1 its inputs (read). One LRW moves an image
//     that fits a frame; a longer one goes as several LRWs cut on the slaves' windows
//     (lrw_split.hpp, cycle_frames.hpp). Expected LRW working counter over the whole image: per
//     slave +2 with outputs, +1 with inputs.
//
// Remapping: assign_pdos()/map_pdo() write 1C12h/1C13h or a mapping object the CiA 301 way
// (subindex 0 to 0, the entries, subindex 0 to the count); call before configure_process_data().
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "master/coe.hpp"
#include "master/lrw_split.hpp"
#include "master/slave_info.hpp"

namespace vdrive::master {

class Master;

struct PdoMapping {
  std::uint16_t pdo = 0;                   // 16xxh / 1Axxh
  std::vector<std::uint32_t> entries;      // index<<16 | subindex<<8 | bit length
  std::uint32_t bits() const;
};

struct SlaveProcessData {
  std::vector<PdoMapping> outputs;         // RxPDOs assigned to SM2
  std::vector<PdoMapping> inputs;          // TxPDOs assigned to SM3
  bool from_coe = false;                   // false: from the SII PDO categories
  std::uint16_t output_bytes = 0, input_bytes = 0;
  std::uint32_t output_logical = 0, input_logical = 0;
  std::uint16_t sm2_start = 0, sm3_start = 0;
  std::uint16_t expected_wkc() const { return static_cast<std::uint16_t>((output_bytes ? 2 : 0) + (input_bytes ? 1 : 0)); }
};

struct ProcessImageLayout {
  std::uint32_t logical_start = 0;
  std::uint32_t output_bytes = 0;          // [logical_start, +output_bytes): every slave's outputs
  std::uint32_t input_bytes = 0;           // then every slave's inputs
  std::uint16_t expected_wkc = 0;          // of one LRW over the whole image
  std::vector<SlaveImage> slaves;          // each slave's FMMU windows: what a piece's counter is
  std::uint32_t size() const { return output_bytes + input_bytes; }
};

// Reads a slave's PDO assignment and mapping over CoE (1C12h/1C13h and the PDOs they list).
// Throws SdoAbort / MailboxError.
void read_pdo_configuration(SdoClient& sdo, SlaveProcessData& out);
// Takes the PDOs of the SII categories (RxPDO with SM 2, TxPDO with SM 3).
void sii_pdo_configuration(const SlaveInfo& info, SlaveProcessData& out);

// Remapping: 1C12h/1C13h := pdos; a mapping object := entries.
void assign_pdos(SdoClient& sdo, std::uint16_t assign_object, std::span<const std::uint16_t> pdos);
void map_pdo(SdoClient& sdo, std::uint16_t pdo, std::span<const std::uint32_t> entries);

// Byte offset of `object` (subindex 0) among `pdos` laid out from byte `base` of the image, or -1.
long pdo_entry_offset(const std::vector<PdoMapping>& pdos, std::uint32_t base, std::uint16_t object);

// A little-endian value at `offset` of the process image.
template <typename T>
T image_get(std::span<const std::uint8_t> image, std::uint32_t offset) {
  T v{};
  std::memcpy(&v, image.data() + offset, sizeof(T));
  return v;
}
template <typename T>
void image_put(std::span<std::uint8_t> image, std::uint32_t offset, T v) {
  std::memcpy(image.data() + offset, &v, sizeof(T));
}

// Configures SM2/SM3 and FMMUs of every slave (in Pre-Op) and returns the image layout. Each
// slave's PDOs come from CoE when it has CoE and answers, otherwise from its SII; `notes` gets one
// line per slave that fell back. Throws MasterError on the wire.
ProcessImageLayout configure_process_data(Master& master, std::vector<std::string>* notes = nullptr);

}  // namespace vdrive::master
