#include "vdrive/web/web_address.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <stdexcept>

namespace vdrive::web {
namespace {

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.';
}

}  // namespace

bool WebAddress::loopback() const {
  if (host == "localhost" || host == "::1") return true;
  in_addr a{};
  return ::inet_pton(AF_INET, host.c_str(), &a) == 1 && (ntohl(a.s_addr) >> 24) == 127;
}

std::string WebAddress::url() const {
  std::string shown = host;
  if (host == "0.0.0.0" || host == "::") {
    char name[256] = {};
    shown = ::gethostname(name, sizeof name - 1) == 0 && name[0] != '\0' ? name : "localhost";
  }
  if (shown.find(':') != std::string::npos) shown = "[" + shown + "]";
  return fmt::format("http://{}:{}/", shown, port);
}

WebAddress parse_web_address(std::string_view text) {
  WebAddress a;
  std::string_view port = text;
  if (const std::size_t colon = text.rfind(':'); colon != std::string_view::npos) {
    std::string_view host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
      host = host.substr(1, host.size() - 2);
      in6_addr v6{};
      if (::inet_pton(AF_INET6, std::string(host).c_str(), &v6) != 1)
        throw std::invalid_argument(fmt::format("'{}': [{}] is not an IPv6 address", text, host));
    } else if (host.empty() || host.find(':') != std::string_view::npos ||
               !std::all_of(host.begin(), host.end(), name_char)) {
      throw std::invalid_argument(
          fmt::format("'{}': expected [ADDR:]PORT, e.g. 8080, 127.0.0.1:8080, 0.0.0.0:8080 or [::1]:8080", text));
    }
    a.host = std::string(host);
  }
  int p = 0;
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), p);
  if (port.empty() || ec != std::errc{} || end != port.data() + port.size() || p < 1 || p > 65535)
    throw std::invalid_argument(fmt::format("'{}': the port must be a number from 1 to 65535", text));
  a.port = p;
  return a;
}

}  // namespace vdrive::web
