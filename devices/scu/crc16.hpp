#pragma once
// The SCU's telegram checksum: CRC-16/CCITT, polynomial 0x1021, start value 0 (the "XMODEM" variant),
// computed from the 256-entry table the manual gives (section 6). Appended low byte first.

#include <cstdint>
#include <span>

namespace cellctl::scu {

[[nodiscard]] std::uint16_t crc16(std::span<const std::uint8_t> bytes) noexcept;

}  // namespace cellctl::scu
