#pragma once
// The one way cellctl asks the operator before something moves (home, `scu move --beyond-travel`,
// and any routine that asks): the question on the terminal, then a line; yes in any case ("yes",
// "Yes", "YES", "y", "Y", spaces around ignored) confirms, anything else or the end of input does not.
// A script confirms beforehand with the command's --yes; without a terminal to ask on nothing is
// assumed.

#include <istream>
#include <string_view>

namespace cellctl::cli {

enum class Confirmation {
  confirmed,    // --yes, or yes typed
  declined,     // anything else typed, or the input ended
  no_terminal,  // not asked: stdin is no terminal and --yes was not given
};

[[nodiscard]] bool is_yes(std::string_view answer) noexcept;

// Prints `question`, then "Type yes and Enter: ", and reads one line from `in`.
[[nodiscard]] bool ask_yes(std::string_view question, std::istream& in);

// confirmed at once when `assumed` (--yes); else asks on the terminal (std::cin) when there is one.
[[nodiscard]] Confirmation confirm(std::string_view question, bool assumed);

}  // namespace cellctl::cli
