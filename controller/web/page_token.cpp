#include "web/page_token.hpp"

#include <fmt/format.h>
#include <sys/random.h>

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace cellctl::web {
namespace {

PageToken long_enough(PageToken t) {
  if (t.token.size() < kMinTokenBytes)
    throw std::runtime_error(fmt::format("{}: the operator page's token has {} bytes; at least {} are needed",
                                         t.origin, t.token.size(), kMinTokenBytes));
  return t;
}

}  // namespace

PageToken page_token(const std::filesystem::path& token_file) {
  if (!token_file.empty()) {
    std::ifstream in(token_file);
    std::string line;
    if (!in || !std::getline(in, line))
      throw std::runtime_error(fmt::format("{}: cannot be read", token_file.string()));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty())
      throw std::runtime_error(fmt::format("{}: holds no token on its first line", token_file.string()));
    return long_enough({line, "file " + token_file.string()});
  }
  if (const char* env = std::getenv("CELLCTL_HTTP_TOKEN"); env && *env)
    return long_enough({env, "CELLCTL_HTTP_TOKEN"});
  return {random_hex(16), "generated"};
}

std::string random_hex(std::size_t bytes) {
  std::vector<unsigned char> raw(bytes);
  std::size_t got = 0;
  while (got < raw.size()) {
    const auto n = getrandom(raw.data() + got, raw.size() - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("getrandom: no random bytes for the operator page's secrets");
    got += static_cast<std::size_t>(n);
  }
  std::string hex;
  for (const auto b : raw) hex += fmt::format("{:02x}", b);
  return hex;
}

bool same_secret(std::string_view given, std::string_view secret) noexcept {
  unsigned diff = given.size() == secret.size() ? 0u : 1u;
  for (std::size_t i = 0; i < secret.size(); ++i)
    diff |= static_cast<unsigned>(static_cast<unsigned char>(i < given.size() ? given[i] : 0) ^
                                  static_cast<unsigned char>(secret[i]));
  return diff == 0 && !secret.empty();
}

}  // namespace cellctl::web
