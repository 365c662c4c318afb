#pragma once
// The operator page's secrets. The token: from a file (its first line), else from CELLCTL_HTTP_TOKEN,
// else a fresh random one (128 bits, hex) that cellctl prints at the start, as a notebook server does.
// A token shorter than kMinTokenBytes is refused, wherever it came from: a short one could be guessed
// over the network, however slowly wrong guesses are answered.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace cellctl::web {

inline constexpr std::size_t kMinTokenBytes = 16;

struct PageToken {
  std::string token;
  std::string origin;  // "file …", "CELLCTL_HTTP_TOKEN", "generated"
};

// Throws std::runtime_error naming the file or the variable when it cannot be read, is empty or is
// too short.
[[nodiscard]] PageToken page_token(const std::filesystem::path& token_file);

// `bytes` random bytes from the kernel (getrandom), as hex: tokens and session ids.
[[nodiscard]] std::string random_hex(std::size_t bytes);

// Compares without stopping at the first difference, so the time taken tells nothing of the secret.
[[nodiscard]] bool same_secret(std::string_view given, std::string_view secret) noexcept;

}  // namespace cellctl::web
