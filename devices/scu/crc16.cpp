#include "scu/crc16.hpp"

#include <array>

namespace cellctl::scu {
namespace {

// Built at compile time from the polynomial; equals the manual's CRC_TABLE entry for entry
// (ScuCrc16.MatchesTheManualsTableAndChecksToZeroWithSwappedCrc in tests/scu/codec_test.cpp checks
// entries 0x01, 0x80 and 0xFF against the printed table).
constexpr std::array<std::uint16_t, 256> make_table() {
  std::array<std::uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned crc = i << 8;
    for (int bit = 0; bit < 8; ++bit) crc = (crc & 0x8000u) ? (crc << 1) ^ 0x1021u : crc << 1;
    table[i] = static_cast<std::uint16_t>(crc);
  }
  return table;
}

constexpr auto kTable = make_table();
static_assert(kTable[1] == 0x1021 && kTable[255] == 0x1EF0, "CRC table must match the manual");

}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes) noexcept {
  std::uint16_t crc = 0;
  for (const auto b : bytes) {
    crc = static_cast<std::uint16_t>(kTable[((crc >> 8) ^ b) & 0xFFu] ^ (crc << 8));
  }
  return crc;
}

}  // namespace cellctl::scu
