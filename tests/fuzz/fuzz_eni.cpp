// libFuzzer target: ENI files (EtherCATConfig XML). Arbitrary bytes are read as a master's ENI,
// matched against the built-in products or served from the ENI alone, and their init commands
// tried on the devices; a broken file must end in a NetworkFileError with a message, never a
// crash, a hang or a sanitizer report.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vdrive/machine/eni_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)vdrive::machine::parse_eni(text, "fuzz.xml", {});
  } catch (const vdrive::machine::NetworkFileError& e) {
    if (std::string_view(e.what()).empty()) __builtin_trap();
  }
  return 0;
}
