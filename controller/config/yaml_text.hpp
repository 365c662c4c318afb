#pragma once
// The bytes under YamlNode: a config or recipe file is read whole, only when it is a readable
// regular file of at most kMaxYamlFileBytes, and its text must be UTF-8 without NUL bytes. Every
// refusal is a ConfigError naming the file, a position and the reason, so that `cellctl check`,
// `cellctl run` and `-c` exit 3 for an unreadable path as for any other bad input.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace cellctl::config {

// 1 MiB: a hundred times the demo recipe; more is no hand-written config and is refused unread.
inline constexpr std::size_t kMaxYamlFileBytes = std::size_t{1} << 20;

// The file's text. A missing or unreadable path, a directory, a device, a pipe or socket, or a file
// over the limit is refused at line 1, column 1 with the reason.
[[nodiscard]] std::string read_yaml_file(const std::filesystem::path& path);

// Refuses the first NUL byte or invalid UTF-8 sequence (overlong, surrogate, above U+10FFFF, cut
// off) at its line and column; columns count bytes from 1, as yaml-cpp's marks do.
void check_yaml_text(std::string_view text, const std::string& file);

}  // namespace cellctl::config
