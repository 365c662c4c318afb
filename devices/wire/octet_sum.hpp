#pragma once
// The arithmetic sum of octets, carries dropped (modulo 256). Two of the cell's protocols check their
// telegrams with it: PROFIBUS FDL's frame check sequence (FCS, over DA..DU) and the SycoTec converter's
// checksum (over the ASCII text after STX). One function, so that both are the same sum by construction.

#include <cstdint>
#include <span>

namespace cellctl::wire {

[[nodiscard]] constexpr std::uint8_t octet_sum(std::span<const std::uint8_t> bytes) noexcept {
  unsigned sum = 0;  // wraps modulo 2^32 on a long span: the low octet is still the sum's
  for (const auto b : bytes) sum += b;
  return static_cast<std::uint8_t>(sum & 0xFFu);
}

}  // namespace cellctl::wire
