#include "vdrive/cli/output_file.hpp"

#include <fmt/core.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "vdrive/cli/cli_error.hpp"
#include "vdrive/cli/exit_codes.hpp"

namespace vdrive::cli {

void write_output_file(const std::string& path, std::span<const std::uint8_t> bytes) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw CliError(kExitFailure, fmt::format("-o: cannot write '{}': {}", path, std::strerror(errno)));
  if (std::fwrite(bytes.data(), 1, bytes.size(), f.get()) != bytes.size() || std::fflush(f.get()) != 0)
    throw CliError(kExitFailure, fmt::format("-o: writing '{}' failed: {}", path, std::strerror(errno)));
}

void write_output_file(const std::string& path, const std::string& text) {
  write_output_file(path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

}  // namespace vdrive::cli
