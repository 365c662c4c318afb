#pragma once
// Non-blocking read/write on a file descriptor mapped to IoResult; shared by SerialLink and PtyPair.

#include <cstdint>
#include <span>

#include "link/link.hpp"

namespace cellctl::link {

IoResult fd_read(int fd, std::span<std::uint8_t> buffer) noexcept;
IoResult fd_write(int fd, std::span<const std::uint8_t> bytes) noexcept;
// Raw 8-bit mode: no echo, no line editing, no CR/LF mapping, no flow control, reads never wait.
// Returns false (errno set) when fd is no terminal.
bool make_raw(int fd) noexcept;

}  // namespace cellctl::link
