#include "config/closest_word.hpp"

#include <algorithm>
#include <vector>

namespace cellctl::config {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // d[i][j]: a's first i characters to b's first j (optimal string alignment).
  const std::size_t w = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * w);
  for (std::size_t i = 0; i <= a.size(); ++i) d[i * w] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      auto& here = d[i * w + j];
      here = std::min({d[(i - 1) * w + j] + 1, d[i * w + j - 1] + 1, d[(i - 1) * w + j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        here = std::min(here, d[(i - 2) * w + j - 2] + 1);
    }
  return d[a.size() * w + b.size()];
}

std::string_view closest_word(std::string_view typed, std::span<const std::string_view> words) {
  std::string_view best;
  std::size_t best_distance = 3;  // only close matches
  for (const auto word : words)
    if (const auto d = edit_distance(typed, word); d < best_distance) best_distance = d, best = word;
  return best;
}

}  // namespace cellctl::config
