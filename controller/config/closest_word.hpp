#pragma once
// "Did you mean …?": the allowed word closest to one that was mistyped (a config key, a cellctl
// command), by edit distance with transpositions (so "reprot" is one step from "report").

#include <cstddef>
#include <span>
#include <string_view>

namespace cellctl::config {

// Insertions, deletions, substitutions and swaps of two neighbours, each one step.
[[nodiscard]] std::size_t edit_distance(std::string_view a, std::string_view b);

// The word of `words` closest to `typed` when it is within 2 steps (a typo, not another word); else empty.
[[nodiscard]] std::string_view closest_word(std::string_view typed, std::span<const std::string_view> words);

}  // namespace cellctl::config
