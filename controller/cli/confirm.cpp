#include "cli/confirm.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <iostream>
#include <string>

namespace cellctl::cli {

bool is_yes(std::string_view answer) noexcept {
  const auto first = answer.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return false;
  answer = answer.substr(first, answer.find_last_not_of(" \t\r") - first + 1);
  const auto is = [&](std::string_view word) {
    if (answer.size() != word.size()) return false;
    for (std::size_t i = 0; i < word.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(answer[i])) != word[i]) return false;
    return true;
  };
  return is("yes") || is("y");
}

bool ask_yes(std::string_view question, std::istream& in) {
  fmt::print("{} Type yes and Enter: ", question);
  std::fflush(stdout);
  std::string answer;
  return std::getline(in, answer) && is_yes(answer);
}

Confirmation confirm(std::string_view question, bool assumed) {
  if (assumed) return Confirmation::confirmed;
  if (isatty(STDIN_FILENO) == 0) return Confirmation::no_terminal;
  return ask_yes(question, std::cin) ? Confirmation::confirmed : Confirmation::declined;
}

}  // namespace cellctl::cli
