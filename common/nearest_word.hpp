#pragma once
// "Did you mean": the candidate nearest to a word a user typed, by edit distance (insertions,
// deletions, substitutions and swaps of two neighbours, one edit each), for messages about
// misspelt keys and names.
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

namespace vdrive {

std::size_t edit_distance(std::string_view a, std::string_view b);

// The nearest of `candidates` within `max_distance` edits (the first of equals), or nullopt.
std::optional<std::string_view> nearest_word(std::string_view word, std::span<const std::string_view> candidates,
                                             std::size_t max_distance = 2);

}  // namespace vdrive
