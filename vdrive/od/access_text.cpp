#include "vdrive/od/access_text.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

#include "vdrive/od/dictionary.hpp"

namespace vdrive::od {

std::string access_text(std::uint16_t bits) {
  const std::uint16_t write = bits & access::kWriteAll;
  if (write == 0) return "ro";
  if (write == access::kWriteAll) return "rw";
  std::vector<std::string_view> states;
  if (write & access::kWritePreOp) states.push_back("PreOp");
  if (write & access::kWriteSafeOp) states.push_back("SafeOp");
  if (write & access::kWriteOp) states.push_back("Op");
  return fmt::format("rw({})", fmt::join(states, ","));
}

std::string_view pdo_text(std::uint16_t bits) {
  if (bits & access::kRxPdoMappable) return "rx";
  if (bits & access::kTxPdoMappable) return "tx";
  return "-";
}

}  // namespace vdrive::od
