#include "vdrive/web/od_api.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "ethercat/al_state.hpp"
#include "ethercat/registers.hpp"
#include "master/coe.hpp"
#include "vdrive/network/network.hpp"
#include "common/number_text.hpp"
#include "vdrive/od/access_text.hpp"
#include "vdrive/od/entry_value.hpp"
#include "vdrive/od/object_store.hpp"

namespace vdrive::web {
namespace {

using json = nlohmann::json;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string hex_of(const std::vector<std::uint8_t>& bytes) {
  std::string out;
  for (const std::uint8_t b : bytes) out += fmt::format("{:02x}", b);
  return out;
}

std::string abort_hex(od::SdoAbort a) { return fmt::format("0x{:08X}", static_cast<std::uint32_t>(a)); }

ApiResult refusal(std::size_t slave, const od::EntryDesc* e, std::uint16_t index, std::uint8_t sub, od::SdoAbort a,
                  std::string_view what) {
  const auto code = static_cast<std::uint32_t>(a);
  const std::string text(master::sdo_abort_text(code));
  const int status = a == od::SdoAbort::NoSuchObject || a == od::SdoAbort::NoSuchSubindex ? 404 : 409;
  return api_error(status,
                   fmt::format("slave {} refused to {} {:04X}h:{:02X}{}: abort 0x{:08X} {}", slave + 1, what, index, sub,
                               e != nullptr ? fmt::format(" ({})", e->name) : std::string(), code, text),
                   {{"abort_code", abort_hex(a)}, {"abort_text", text}});
}

ecat::AlState al_state_of(network::Network& network, std::size_t slave) {
  return static_cast<ecat::AlState>(network.esc(slave).peek_u16(ecat::reg::kAlStatus) & ecat::reg::kAlStateBits);
}

}  // namespace

std::optional<std::uint32_t> parse_object_number(const std::string& text, std::uint32_t max) {
  // The manuals' "6040h" is hex too.
  const bool prefixed = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const bool suffixed = !prefixed && text.size() > 1 && (text.back() == 'h' || text.back() == 'H');
  const std::optional<std::uint64_t> v = parse_unsigned(suffixed ? "0x" + text.substr(0, text.size() - 1) : text);
  if (!v || *v > max) return std::nullopt;
  return static_cast<std::uint32_t>(*v);
}

json entry_json(const od::EntryDesc& e) {
  json j = {{"index", e.index}, {"subindex", e.subindex}, {"name", e.name}, {"type", std::string(od::short_name(e.type))},
            {"bits", e.bit_length}, {"access", od::access_text(e.access)}};
  const std::string_view pdo = od::pdo_text(e.access);
  j["pdo"] = pdo == "-" ? "" : std::string(pdo);
  j["min"] = e.min ? json(*e.min) : json(nullptr);
  j["max"] = e.max ? json(*e.max) : json(nullptr);
  j["default"] = decode_value(e, e.default_value).at("value");
  j["units"] = e.units;
  return j;
}

json list_entries(const od::Dictionary& dictionary, const std::string& query, std::size_t limit) {
  // An index query: "6040", "0x6040", "6040h", optionally ":sub".
  std::optional<std::uint32_t> index, sub;
  std::string q = query;
  if (const std::size_t colon = q.find(':'); colon != std::string::npos) {
    sub = parse_object_number(q.substr(colon + 1), 0xFF);
    q = q.substr(0, colon);
  }
  std::optional<std::uint32_t> as_hex = parse_object_number(q.rfind("0x", 0) == 0 || q.rfind("0X", 0) == 0 ? q : "0x" + q, 0xFFFF);
  if (as_hex && !q.empty()) index = as_hex;
  std::vector<std::string> words;
  std::istringstream in(lower(query));
  for (std::string w; in >> w;) words.push_back(w);

  json list = json::array();
  bool truncated = false;
  for (const od::ObjectDesc& o : dictionary.objects()) {
    for (const od::EntryDesc& e : o.entries) {
      bool match = query.empty();
      if (!match && index) match = e.index == *index && (!sub || e.subindex == *sub);
      if (!match && !words.empty()) {
        const std::string name = lower(o.name + " " + e.name);
        match = std::all_of(words.begin(), words.end(), [&](const std::string& w) { return name.find(w) != std::string::npos; });
      }
      if (!match) continue;
      if (list.size() >= limit) {
        truncated = true;
        break;
      }
      list.push_back(entry_json(e));
    }
    if (truncated) break;
  }
  return {{"objects", std::move(list)}, {"truncated", truncated}};
}

json decode_value(const od::EntryDesc& e, const std::vector<std::uint8_t>& bytes) {
  json value;
  if (e.type == od::DataType::VisibleString) {
    const auto nul = std::find(bytes.begin(), bytes.end(), std::uint8_t{0});
    // Manual texts are UTF-8; the server dumps replies replacing anything else.
    value = std::string(bytes.begin(), nul);
  } else if (e.type == od::DataType::OctetString) {
    value = hex_of(bytes);
  } else if (e.type == od::DataType::Real32 && bytes.size() == 4) {
    float f = 0;
    std::memcpy(&f, bytes.data(), 4);
    value = std::isfinite(f) ? json(static_cast<double>(f)) : json(nullptr);
  } else if (e.type == od::DataType::Unsigned64) {
    value = static_cast<std::uint64_t>(od::entry_integer(e, bytes));
  } else {
    value = od::entry_integer(e, bytes);
  }
  return {{"value", std::move(value)}, {"hex", hex_of(bytes)}};
}

std::variant<std::vector<std::uint8_t>, ApiResult> encode_value(const od::EntryDesc& e, const json& body) {
  if (!body.is_object()) return api_error(400, "the body must be a JSON object: {\"value\": ...} or {\"hex\": \"...\"}");
  for (const auto& [key, v] : body.items())
    if (key != "value" && key != "hex") return api_error(400, fmt::format("\"{}\" does not belong in an object write (value or hex)", key));
  if (body.contains("value") == body.contains("hex")) return api_error(400, "give exactly one of \"value\" and \"hex\"");
  std::vector<std::uint8_t> bytes;
  if (body.contains("hex")) {
    const json& h = body.at("hex");
    if (!h.is_string()) return api_error(400, "\"hex\" must be a string of hex digit pairs, least significant byte first");
    const std::string s = h.get<std::string>();
    if (s.size() % 2 != 0 || s.size() > 2 * 1024) return api_error(400, "\"hex\" must be pairs of hex digits (at most 1024 bytes)");
    for (std::size_t i = 0; i < s.size(); i += 2) {
      unsigned b = 0;
      const auto [end, ec] = std::from_chars(s.data() + i, s.data() + i + 2, b, 16);
      if (ec != std::errc{} || end != s.data() + i + 2) return api_error(400, fmt::format("\"hex\": '{}' is not a hex byte", s.substr(i, 2)));
      bytes.push_back(static_cast<std::uint8_t>(b));
    }
    return bytes;
  }
  const json& v = body.at("value");
  if (e.type == od::DataType::VisibleString) {
    if (!v.is_string()) return api_error(400, fmt::format("\"value\": {:04X}h:{:02X} is a string", e.index, e.subindex));
    const std::string s = v.get<std::string>();
    return std::vector<std::uint8_t>(s.begin(), s.end());
  }
  if (e.type == od::DataType::OctetString) return api_error(400, "\"value\": an octet string is written as {\"hex\": \"...\"}");
  if (e.type == od::DataType::Real32) {
    if (!v.is_number()) return api_error(400, "\"value\": expected a number");
    const auto f = static_cast<float>(v.get<double>());
    bytes.resize(4);
    std::memcpy(bytes.data(), &f, 4);
    return bytes;
  }
  std::int64_t n = 0;
  if (v.is_boolean()) n = v.get<bool>() ? 1 : 0;
  else if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) && e.type != od::DataType::Unsigned64)
      return api_error(400, fmt::format("\"value\": {} does not fit {}", u, od::short_name(e.type)));
    n = static_cast<std::int64_t>(u);
  } else if (v.is_number_integer()) n = v.get<std::int64_t>();
  else return api_error(400, fmt::format("\"value\": expected an integer for {} {:04X}h:{:02X}, got {}", od::short_name(e.type), e.index, e.subindex, v.dump()));
  const std::size_t size = e.value_bytes;
  const unsigned bits = std::min<unsigned>(e.bit_length, 64);
  if (bits < 64) {
    const od::IntegerRange type = od::integer_range(bits, od::is_signed(e.type));
    if (n < type.min || n > type.max)
      return api_error(400, fmt::format("\"value\": {} does not fit {} {:04X}h:{:02X} ({}..{})", n, od::short_name(e.type), e.index,
                                        e.subindex, type.min, type.max));
  }
  bytes.resize(size);
  for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(n) >> (8 * std::min<std::size_t>(i, 7)));
  return bytes;
}

ApiResult read_entry(network::Network& network, std::size_t slave, std::uint16_t index, std::uint8_t sub) {
  const od::ObjectStore& store = network.firmware(slave).objects();
  const od::EntryDesc* e = store.dictionary().find(index, sub);
  std::vector<std::uint8_t> bytes(e != nullptr ? std::max<std::size_t>(e->value_bytes, 1) : 1);
  std::size_t written = 0;
  const od::SdoAbort a = store.read(index, sub, bytes, written, al_state_of(network, slave));
  if (a != od::SdoAbort::Ok || e == nullptr) return refusal(slave, e, index, sub, a == od::SdoAbort::Ok ? od::SdoAbort::NoSuchSubindex : a, "read");
  bytes.resize(written);
  json j = entry_json(*e);
  const json v = decode_value(*e, bytes);
  j["value"] = v.at("value");
  j["hex"] = v.at("hex");
  return {200, std::move(j)};
}

ApiResult write_entry(network::Network& network, std::size_t slave, std::uint16_t index, std::uint8_t sub,
                      const std::vector<std::uint8_t>& data) {
  od::ObjectStore& store = network.firmware(slave).objects();
  const od::EntryDesc* e = store.dictionary().find(index, sub);
  const od::SdoAbort a = store.write(index, sub, data, al_state_of(network, slave));
  if (a != od::SdoAbort::Ok) return refusal(slave, e, index, sub, a, "write");
  return read_entry(network, slave, index, sub);
}

}  // namespace vdrive::web
