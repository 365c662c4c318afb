#pragma once
// The emulated encoder's EEPROM kept in a small text file, so that a preset offset, a direction set
// on the fly, a Teach-In result and a bus-set address survive an emulator restart as they survive a
// power cycle. Emulator side only (load at construction, save when a value changed — never in the
// master's cycle).

#include <filesystem>

#include "encoder/encoder_device.hpp"

namespace cellctl::encoder {

// Missing file: defaults. Malformed file: std::runtime_error naming the file, line and key.
[[nodiscard]] NonVolatile load_eeprom(const std::filesystem::path& path);
// Writes a temporary file and renames it over `path`; false when that fails.
[[nodiscard]] bool save_eeprom(const std::filesystem::path& path, const NonVolatile& nv) noexcept;

}  // namespace cellctl::encoder
