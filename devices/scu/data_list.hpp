#pragma once
// The SCU's data list (manual 4.3): which data IDs exist, their types and sizes, which IDs are groups
// (last hex digit 0 → all elements of the block, in order), and which are writable (0x3xxx only).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace cellctl::scu {

enum class DataType : std::uint8_t {
  u8,
  u16,
  u32,
  i32,
  f32,
  string31,        // firmware info
  string36,        // configuration info
  cyclic_object,   // UINT16[12]: six write IDs, six read IDs
  user_positions,  // ACTUATOR_POSITIONS: 26 × INT32
};

struct DataElement {
  std::uint16_t id;
  DataType type;
  std::string_view name;
};

[[nodiscard]] std::size_t size_of(DataType t) noexcept;

// The element with exactly this ID, or nullptr.
[[nodiscard]] const DataElement* find_element(std::uint16_t id) noexcept;
// The elements an ID addresses: itself when it is an element, else — for an ID ending in hex 0 — the
// elements of its block in order. Empty for an unknown ID.
[[nodiscard]] std::span<const DataElement> elements_of(std::uint16_t id) noexcept;
// Bytes an RG of this ID returns (0 for an unknown ID).
[[nodiscard]] std::size_t value_size(std::uint16_t id) noexcept;
// Only remote data elements (0x3xxx) may be written with RT or as cyclic write data.
[[nodiscard]] constexpr bool is_remote_data(std::uint16_t id) noexcept {
  return (id & 0xF000u) == 0x3000u;
}

// The IDs the program uses by name (actuator a = 1..6, function f = 1..10, cyclic object k = 1..5).
namespace data_id {
inline constexpr std::uint16_t kFirmwareInfo = 0x0001;
inline constexpr std::uint16_t kConfigurationInfo = 0x0002;
inline constexpr std::uint16_t kPositions = 0x0010;  // group: all six
inline constexpr std::uint16_t kStatus1 = 0x0170;    // group: all six
inline constexpr std::uint16_t kErrorCode = 0x00D1;  // the latest error word; 0x00D2..D5 history
[[nodiscard]] constexpr std::uint16_t position(int a) noexcept {
  return static_cast<std::uint16_t>(0x0010 + a);
}
[[nodiscard]] constexpr std::uint16_t status1(int a) noexcept {
  return static_cast<std::uint16_t>(0x0170 + a);
}
[[nodiscard]] constexpr std::uint16_t status2(int a) noexcept {
  return static_cast<std::uint16_t>(0x00E0 + a);
}
[[nodiscard]] constexpr std::uint16_t error_code(int n) noexcept {
  return static_cast<std::uint16_t>(0x00D0 + n);
}
[[nodiscard]] constexpr std::uint16_t cyclic_object(int k) noexcept {
  return static_cast<std::uint16_t>(0x3000 + k);
}
[[nodiscard]] constexpr std::uint16_t remote_speed(int f) noexcept {
  return static_cast<std::uint16_t>(0x3010 + f);
}
[[nodiscard]] constexpr std::uint16_t remote_position(int a) noexcept {
  return static_cast<std::uint16_t>(0x3020 + a);
}
}  // namespace data_id

}  // namespace cellctl::scu
