#pragma once
// Writes fixed-width integers into a caller-owned buffer with explicit endianness. Writing past the
// end of the buffer writes nothing and latches !ok(): encoders never allocate and never overrun.

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>

namespace cellctl::wire {

class ByteWriter {
 public:
  explicit ByteWriter(std::span<std::uint8_t> out) noexcept : out_(out) {}

  void u8(std::uint8_t v) noexcept {
    if (room(1)) out_[pos_++] = v;
  }
  template <std::integral T>
  void le(T v) noexcept {
    write(v, false);
  }
  template <std::integral T>
  void be(T v) noexcept {
    write(v, true);
  }
  void le_float(float v) noexcept { le(std::bit_cast<std::uint32_t>(v)); }
  void bytes(std::span<const std::uint8_t> b) noexcept {
    if (!room(b.size())) return;
    for (auto x : b) out_[pos_++] = x;
  }

  [[nodiscard]] bool ok() const noexcept { return ok_; }
  [[nodiscard]] std::size_t size() const noexcept { return pos_; }
  [[nodiscard]] std::span<const std::uint8_t> written() const noexcept { return out_.first(pos_); }
  // Write access to what has been written so far, for a length field filled in afterwards.
  [[nodiscard]] std::span<std::uint8_t> written_mutable() noexcept { return out_.first(pos_); }

 private:
  bool room(std::size_t n) noexcept {
    if (!ok_ || n > out_.size() - pos_) ok_ = false;
    return ok_;
  }
  template <std::integral T>
  void write(T v, bool big_endian) noexcept {
    using U = std::make_unsigned_t<T>;
    constexpr std::size_t n = sizeof(T);
    if (!room(n)) return;
    const auto u = static_cast<U>(v);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t shift = big_endian ? (n - 1 - i) * 8 : i * 8;
      out_[pos_++] = static_cast<std::uint8_t>((u >> shift) & 0xFFu);
    }
  }

  std::span<std::uint8_t> out_;
  std::size_t pos_ = 0;
  bool ok_ = true;
};

}  // namespace cellctl::wire
