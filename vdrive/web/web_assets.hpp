#pragma once
// The page's files compiled into the program (cmake/embed_files.cmake): index.html, app.js,
// style.css, openapi.json and Debian's Chart.js as /lib/chart.min.js. With VDRIVE_WEB_ASSETS set
// to a folder, the page's own files are read from there on every request instead (to work on the
// page without rebuilding).
#include <optional>
#include <string>
#include <string_view>

namespace vdrive::web {

struct Asset {
  std::string body;
  std::string content_type;
};

// `url` as requested ("/", "/app.js", "/lib/chart.min.js"); nullopt if there is no such file.
std::optional<Asset> find_asset(std::string_view url);

}  // namespace vdrive::web
