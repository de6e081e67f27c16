#pragma once
// Where the web server listens: `--web [ADDR:]PORT`. ADDR defaults to 127.0.0.1 (this machine
// only); any other address serves other machines too, and then changes need the start-up token.
#include <string>
#include <string_view>

namespace vdrive::web {

struct WebAddress {
  std::string host = "127.0.0.1";
  int port = 0;
  // 127.0.0.0/8, ::1 or localhost: only this machine can connect.
  bool loopback() const;
  // "http://127.0.0.1:8080/" (an unspecified host is shown as this machine's name).
  std::string url() const;
};

// "8080", "127.0.0.1:8080", "0.0.0.0:8080", "[::1]:8080", "localhost:8080". Throws
// std::invalid_argument naming what was wrong (port 1-65535; an IPv4, [IPv6] or a name).
WebAddress parse_web_address(std::string_view text);

}  // namespace vdrive::web
