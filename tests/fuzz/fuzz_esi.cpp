// libFuzzer target: ESI files. Arbitrary bytes are parsed as an EtherCATInfo document; every device
// that reads is imported (profile, dictionary, SII image). A broken file must end in an EsiError
// (or ProfileError) with a message, never a crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "vdrive/esi/esi_error.hpp"
#include "vdrive/esi/esi_import.hpp"
#include "vdrive/esi/esi_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const std::vector<vdrive::esi::EsiDevice> devices = vdrive::esi::parse_esi(text, "fuzz.xml");
    for (const vdrive::esi::EsiDevice& d : devices) {
      try {
        (void)vdrive::esi::import_device(d);
      } catch (const vdrive::profile::ProfileError& e) {
        if (std::string_view(e.what()).empty()) __builtin_trap();
      }
    }
  } catch (const vdrive::profile::ProfileError& e) {
    if (std::string_view(e.what()).empty()) __builtin_trap();
  }
  return 0;
}
