#pragma once
// The object dictionary through the web API: a slave's entries listed and searched (from its
// immutable dictionary, any thread), one entry read or written on the loop thread through the
// slave's ObjectStore in its present AL state, so the same access rights, ranges and abort codes
// apply as to a master's SDO (Init counts as Pre-Op, as the store does). Not through the SDO
// server: a write of 1010h/1011h changes the object but does not store or restore parameters.
#include <cstdint>
#include <optional>
#include <variant>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vdrive/od/dictionary.hpp"
#include "vdrive/web/api_result.hpp"

namespace vdrive::network { class Network; }

namespace vdrive::web {

// "0x6040", "6040h", "24640" -> the number; nullopt if it is none or above `max`.
std::optional<std::uint32_t> parse_object_number(const std::string& text, std::uint32_t max);

// Entries whose index ("6040", "0x6040", "6040:1") or name (every word, case-insensitive) match
// `query`; all for an empty query. At most `limit`, then "truncated": true.
nlohmann::json list_entries(const od::Dictionary& dictionary, const std::string& query, std::size_t limit = 500);
nlohmann::json entry_json(const od::EntryDesc& entry);

// The bytes a JSON value stands for in `entry` ({"value": 5}, {"value": "text"}, {"hex": "0a00"});
// an api_error(400) naming the problem when it cannot be one.
std::variant<std::vector<std::uint8_t>, ApiResult> encode_value(const od::EntryDesc& entry, const nlohmann::json& body);
// The entry's bytes as {"value": ..., "hex": "..."}.
nlohmann::json decode_value(const od::EntryDesc& entry, const std::vector<std::uint8_t>& bytes);

// Loop thread. `slave` from 0.
ApiResult read_entry(network::Network& network, std::size_t slave, std::uint16_t index, std::uint8_t subindex);
ApiResult write_entry(network::Network& network, std::size_t slave, std::uint16_t index, std::uint8_t subindex,
                      const std::vector<std::uint8_t>& data);

}  // namespace vdrive::web
