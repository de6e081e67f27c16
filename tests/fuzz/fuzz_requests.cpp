// libFuzzer target: what a user or a remote program sends at runtime, as text: the control
// socket's JSON lines, the DDS control requests, and the web API's parts that read a request
// (--web addresses, object numbers from the path, object searches, and object write bodies encoded
// for an entry of a real dictionary and decoded again). Every input must end in a value or the
// surface's own error, never a crash, a hang or another exception.
//
// Input: byte 0 picks the surface; the rest is the text.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "vdrive/control/control_protocol.hpp"
#include "vdrive/od/dictionary_cache.hpp"
#include "vdrive/profile/profile_loader.hpp"
#include "vdrive/telemetry/telemetry_request.hpp"
#include "vdrive/web/od_api.hpp"
#include "vdrive/web/web_address.hpp"

namespace {

const vdrive::od::Dictionary& dictionary() {
  static const vdrive::profile::ProductProfile profile = vdrive::profile::load_profile("a6b");
  static const std::shared_ptr<const vdrive::od::Dictionary> d = vdrive::od::shared_dictionary(profile);
  return *d;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  switch (data[0] % 6) {
    case 0:
      try {
        (void)vdrive::control::parse_request(text);
      } catch (const vdrive::control::ProtocolError&) {
      }
      break;
    case 1:
      try {
        (void)vdrive::telemetry::parse_telemetry_request(text);
      } catch (const vdrive::control::ProtocolError&) {
      }
      break;
    case 2:
      try {
        (void)vdrive::web::parse_web_address(text);
      } catch (const std::invalid_argument&) {
      }
      break;
    case 3:
      (void)vdrive::web::parse_object_number(text, 0xFFFF);
      break;
    case 4:
      (void)vdrive::web::list_entries(dictionary(), text, 50).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      break;
    case 5: {
      // The first two bytes choose the entry (by position in the dictionary); the rest is the body.
      if (text.size() < 2) return 0;
      const auto objects = dictionary().objects();
      const auto& object = objects[(static_cast<std::uint8_t>(text[0]) * 256u + static_cast<std::uint8_t>(text[1])) % objects.size()];
      if (object.entries.empty()) return 0;
      const vdrive::od::EntryDesc& entry = object.entries[static_cast<std::uint8_t>(text[0]) % object.entries.size()];
      const nlohmann::json body = nlohmann::json::parse(text.substr(2), nullptr, false);
      if (body.is_discarded()) return 0;
      const auto encoded = vdrive::web::encode_value(entry, body);
      if (const auto* bytes = std::get_if<std::vector<std::uint8_t>>(&encoded))
        (void)vdrive::web::decode_value(entry, *bytes).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      break;
    }
  }
  return 0;
}
