#pragma once
// Reads fixed-width integers from a byte span with the endianness spelled out at every call.
// Reading past the end never touches memory: it yields 0 and latches !ok(), so a decoder can
// read a whole structure and check once at the end.

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>

namespace cellctl::wire {

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) noexcept : bytes_(bytes) {}

  [[nodiscard]] std::uint8_t u8() noexcept { return take(1) ? bytes_[pos_ - 1] : 0; }

  template <std::integral T>
  [[nodiscard]] T le() noexcept {
    return read<T>(false);
  }
  template <std::integral T>
  [[nodiscard]] T be() noexcept {
    return read<T>(true);
  }
  [[nodiscard]] float le_float() noexcept { return std::bit_cast<float>(le<std::uint32_t>()); }

  // The next n bytes as a view; an empty span (and !ok()) when fewer remain.
  [[nodiscard]] std::span<const std::uint8_t> bytes(std::size_t n) noexcept {
    if (!take(n)) return {};
    return bytes_.subspan(pos_ - n, n);
  }
  [[nodiscard]] std::span<const std::uint8_t> rest() noexcept { return bytes(remaining()); }

  [[nodiscard]] bool ok() const noexcept { return ok_; }
  [[nodiscard]] std::size_t offset() const noexcept { return pos_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return bytes_.size() - pos_; }
  [[nodiscard]] bool at_end() const noexcept { return pos_ == bytes_.size(); }

 private:
  bool take(std::size_t n) noexcept {
    if (!ok_ || n > remaining()) {
      ok_ = false;
      return false;
    }
    pos_ += n;
    return true;
  }

  template <std::integral T>
  T read(bool big_endian) noexcept {
    using U = std::make_unsigned_t<T>;
    constexpr std::size_t n = sizeof(T);
    if (!take(n)) return T{0};
    U value = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t shift = big_endian ? (n - 1 - i) * 8 : i * 8;
      value = static_cast<U>(value | static_cast<U>(static_cast<U>(bytes_[pos_ - n + i]) << shift));
    }
    return static_cast<T>(value);
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace cellctl::wire
