#include "command/command_source.hpp"

namespace cellctl::command {

std::string_view to_string(CommandSource::Origin o) noexcept {
  switch (o) {
    case CommandSource::Origin::terminal:
      return "terminal";
    case CommandSource::Origin::web:
      return "web";
    case CommandSource::Origin::plant:
      return "plant";
    case CommandSource::Origin::signal:
      return "signal";
  }
  return "?";
}

std::string CommandSource::words() const {
  std::string s(to_string(origin));
  if (!where.empty()) s += " " + where;
  if (!who.empty()) s += (origin == Origin::plant ? " (by " : " (") + who + ")";
  return s;
}

std::string capped(std::string_view text, std::size_t max) {
  std::size_t end = text.size();
  if (end > max) {
    end = max;
    while (end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0u) == 0x80u) --end;  // not mid-character
  }
  std::string s(text.substr(0, end));
  for (auto& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = '?';  // no control characters from outside
  return end < text.size() ? s + "…" : s;
}

}  // namespace cellctl::command
