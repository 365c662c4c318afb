#pragma once
// Who commanded: every command in the journal, on the plant's `response` and on the page says where it
// came from — the terminal, the web page (the client's address and which token), the plant (the
// topic, and the payload's `by` when given). Names from outside are capped before they are kept, so
// a long one is never echoed whole.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace cellctl::command {

struct CommandSource {
  enum class Origin : std::uint8_t { terminal, web, plant, signal };
  Origin origin = Origin::terminal;
  std::string where;  // web: "address:port"; plant: the topic; terminal, signal: empty
  std::string who;    // web: which token ("token #1"); plant: the payload's "by"; may be empty

  // "terminal", "web 127.0.0.1:51234 (token #1)", "plant cell/cmd/hold (by MES-7)".
  [[nodiscard]] std::string words() const;
};

[[nodiscard]] std::string_view to_string(CommandSource::Origin o) noexcept;

// A name from outside as it may be kept and shown: at most `max` bytes of `text` (cut on a UTF-8
// boundary, "…" added when cut), control characters replaced by '?'.
[[nodiscard]] std::string capped(std::string_view text, std::size_t max = 64);

}  // namespace cellctl::command
