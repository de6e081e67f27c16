#pragma once
// Writing a command's `-o FILE` output: the whole content or a CliError (exit 1) naming the file
// and the system's reason, so a full disk or a missing directory is never a silent short file.
#include <cstdint>
#include <span>
#include <string>

namespace vdrive::cli {

void write_output_file(const std::string& path, std::span<const std::uint8_t> bytes);
void write_output_file(const std::string& path, const std::string& text);

}  // namespace vdrive::cli
