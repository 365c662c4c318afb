#pragma once
// The operator page's command token: from a file (its first line), else from CELLCTL_HTTP_TOKEN, else
// a fresh random one (128 bits from /dev/urandom, hex) that cellctl prints at the start, as a
// notebook server does. Throws std::runtime_error naming the file when it cannot be read or is empty.

#include <filesystem>
#include <string>

namespace cellctl::web {

struct PageToken {
  std::string token;
  std::string origin;  // "file …", "CELLCTL_HTTP_TOKEN", "generated"
};

[[nodiscard]] PageToken page_token(const std::filesystem::path& token_file);

}  // namespace cellctl::web
