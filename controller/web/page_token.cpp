#include "web/page_token.hpp"

#include <fmt/format.h>

#include <array>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace cellctl::web {

PageToken page_token(const std::filesystem::path& token_file) {
  if (!token_file.empty()) {
    std::ifstream in(token_file);
    std::string line;
    if (!in || !std::getline(in, line))
      throw std::runtime_error(fmt::format("{}: cannot be read", token_file.string()));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty())
      throw std::runtime_error(fmt::format("{}: holds no token on its first line", token_file.string()));
    return {line, "file " + token_file.string()};
  }
  if (const char* env = std::getenv("CELLCTL_HTTP_TOKEN"); env && *env) return {env, "CELLCTL_HTTP_TOKEN"};
  std::array<unsigned char, 16> bytes{};
  std::ifstream random("/dev/urandom", std::ios::binary);
  if (!random.read(reinterpret_cast<char*>(bytes.data()), bytes.size()))
    throw std::runtime_error("/dev/urandom: cannot be read for the page's token");
  std::string hex;
  for (const auto b : bytes) hex += fmt::format("{:02x}", b);
  return {hex, "generated"};
}

}  // namespace cellctl::web
