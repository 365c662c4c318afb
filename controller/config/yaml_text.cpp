#include "config/yaml_text.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "config/yaml_node.hpp"

namespace cellctl::config {
namespace {

[[noreturn]] void refuse_path(const std::filesystem::path& path, const std::string& reason) {
  throw ConfigError(path.string(), 1, 1, "", "cannot read the file: " + reason);
}

// Closes the descriptor on every way out.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) noexcept : fd_(fd) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  [[nodiscard]] int get() const noexcept { return fd_; }

 private:
  int fd_;
};

// Length of the UTF-8 sequence starting at text[i], 0 when it is invalid.
std::size_t utf8_sequence(std::string_view text, std::size_t i) noexcept {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t n = 0;
  std::uint32_t cp = 0;
  if (b0 >= 0xC2 && b0 <= 0xDF)
    n = 2, cp = b0 & 0x1Fu;
  else if (b0 >= 0xE0 && b0 <= 0xEF)
    n = 3, cp = b0 & 0x0Fu;
  else if (b0 >= 0xF0 && b0 <= 0xF4)
    n = 4, cp = b0 & 0x07u;
  else
    return 0;  // a continuation byte, an overlong lead (C0, C1) or beyond U+10FFFF (F5..FF)
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0u) != 0x80u) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3Fu);
  }
  const bool overlong = (n == 3 && cp < 0x800) || (n == 4 && cp < 0x10000);
  const bool surrogate = cp >= 0xD800 && cp <= 0xDFFF;
  if (overlong || surrogate || cp > 0x10FFFF) return 0;
  return n;
}

[[noreturn]] void refuse_at(std::string_view text, std::size_t offset, const std::string& file,
                            const std::string& rule) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < offset; ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  throw ConfigError(file, line, static_cast<int>(offset - line_start) + 1, "", rule);
}

}  // namespace

std::string read_yaml_file(const std::filesystem::path& path) {
  // O_NONBLOCK: opening a FIFO with no writer must not hang; regular files ignore it.
  const FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK));
  if (fd.get() < 0) refuse_path(path, std::strerror(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) refuse_path(path, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) refuse_path(path, "it is a directory");
  if (!S_ISREG(st.st_mode)) refuse_path(path, "it is not a regular file (a device, a pipe or a socket)");
  const auto too_big = [&](std::size_t size) {
    refuse_path(path,
                fmt::format("it is {} bytes, over the limit of {} bytes (1 MiB)", size, kMaxYamlFileBytes));
  };
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxYamlFileBytes)
    too_big(static_cast<std::size_t>(st.st_size));
  // Read up to one byte past the limit: a file that grows while it is read is refused too.
  std::string text(kMaxYamlFileBytes + 1, '\0');
  std::size_t size = 0;
  while (size < text.size()) {
    const ssize_t n = ::read(fd.get(), text.data() + size, text.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) refuse_path(path, std::strerror(errno));
    if (n == 0) break;
    size += static_cast<std::size_t>(n);
  }
  if (size > kMaxYamlFileBytes) too_big(size);
  text.resize(size);
  return text;
}

void check_yaml_text(std::string_view text, const std::string& file) {
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '\0')
      refuse_at(text, i, file, "NUL byte: the file must be UTF-8 text (is it UTF-16 or binary?)");
    const std::size_t n = utf8_sequence(text, i);
    if (n == 0)
      refuse_at(text, i, file,
                fmt::format("invalid UTF-8 (byte 0x{:02X}): the file must be UTF-8 text",
                            static_cast<unsigned char>(text[i])));
    i += n;
  }
}

}  // namespace cellctl::config
