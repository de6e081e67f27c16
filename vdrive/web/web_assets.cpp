#include "vdrive/web/web_assets.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace vdrive::web {
namespace assets {
struct EmbeddedFile { std::string_view url; const unsigned char* data; std::size_t size; };
const EmbeddedFile* find_embedded(std::string_view url);
}  // namespace assets

namespace {

std::string content_type(std::string_view url) {
  const auto ends = [&](std::string_view s) { return url.size() >= s.size() && url.substr(url.size() - s.size()) == s; };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  if (ends(".json")) return "application/json";
  if (ends(".svg")) return "image/svg+xml";
  if (ends(".png")) return "image/png";
  return "application/octet-stream";
}

// Only plain names of the folder: nothing that climbs out of it.
bool plain_name(std::string_view name) {
  if (name.empty() || name.front() == '.') return false;
  for (const char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '_')) return false;
  return name.find("..") == std::string_view::npos;
}

}  // namespace

std::optional<Asset> find_asset(std::string_view url) {
  if (url == "/") url = "/index.html";
  const char* dir = std::getenv("VDRIVE_WEB_ASSETS");
  if (dir != nullptr && *dir != '\0' && url.size() > 1 && plain_name(url.substr(1))) {
    std::ifstream in(std::string(dir) + "/" + std::string(url.substr(1)), std::ios::binary);
    if (in) {
      std::ostringstream s;
      s << in.rdbuf();
      return Asset{s.str(), content_type(url)};
    }
  }
  if (const assets::EmbeddedFile* f = assets::find_embedded(url))
    return Asset{std::string(reinterpret_cast<const char*>(f->data), f->size), content_type(url)};
  return std::nullopt;
}

}  // namespace vdrive::web
