#include "scu/data_list.hpp"

#include <algorithm>
#include <array>

namespace cellctl::scu {
namespace {

using T = DataType;

// Sorted by ID, so that a block's elements are contiguous and follow their group ID.
constexpr std::array kElements = std::to_array<DataElement>({
    {0x0001, T::string31, "firmware info"},
    {0x0002, T::string36, "configuration info"},
    {0x0011, T::i32, "position A1"},
    {0x0012, T::i32, "position A2"},
    {0x0013, T::i32, "position A3"},
    {0x0014, T::i32, "position A4"},
    {0x0015, T::i32, "position A5"},
    {0x0016, T::i32, "position A6"},
    {0x0020, T::u8, "binary inputs"},
    {0x0031, T::u16, "analogue input 1"},
    {0x0032, T::u16, "analogue input 2"},
    {0x0033, T::u16, "analogue input 3"},
    {0x0034, T::u16, "analogue input 4"},
    {0x0040, T::u32, "keys"},
    {0x0061, T::u32, "relay in cycles A1"},
    {0x0062, T::u32, "relay in cycles A2"},
    {0x0063, T::u32, "relay in cycles A3"},
    {0x0064, T::u32, "relay in cycles A4"},
    {0x0065, T::u32, "relay in cycles A5"},
    {0x0066, T::u32, "relay in cycles A6"},
    {0x0071, T::u32, "relay out cycles A1"},
    {0x0072, T::u32, "relay out cycles A2"},
    {0x0073, T::u32, "relay out cycles A3"},
    {0x0074, T::u32, "relay out cycles A4"},
    {0x0075, T::u32, "relay out cycles A5"},
    {0x0076, T::u32, "relay out cycles A6"},
    {0x0081, T::u32, "actuator errors A1"},
    {0x0082, T::u32, "actuator errors A2"},
    {0x0083, T::u32, "actuator errors A3"},
    {0x0084, T::u32, "actuator errors A4"},
    {0x0085, T::u32, "actuator errors A5"},
    {0x0086, T::u32, "actuator errors A6"},
    {0x008F, T::u32, "total over-current count"},
    {0x0091, T::u32, "cumulated stroke A1"},
    {0x0092, T::u32, "cumulated stroke A2"},
    {0x0093, T::u32, "cumulated stroke A3"},
    {0x0094, T::u32, "cumulated stroke A4"},
    {0x0095, T::u32, "cumulated stroke A5"},
    {0x0096, T::u32, "cumulated stroke A6"},
    {0x00A1, T::u16, "current A1"},
    {0x00A2, T::u16, "current A2"},
    {0x00A3, T::u16, "current A3"},
    {0x00A4, T::u16, "current A4"},
    {0x00A5, T::u16, "current A5"},
    {0x00A6, T::u16, "current A6"},
    {0x00B1, T::u16, "max current A1"},
    {0x00B2, T::u16, "max current A2"},
    {0x00B3, T::u16, "max current A3"},
    {0x00B4, T::u16, "max current A4"},
    {0x00B5, T::u16, "max current A5"},
    {0x00B6, T::u16, "max current A6"},
    {0x00BF, T::u16, "max total current"},
    {0x00C0, T::u8, "max temperature rectifier/FET"},
    {0x00C1, T::u32, "over-temperature count"},
    {0x00D1, T::u32, "error code (latest)"},
    {0x00D2, T::u32, "error code history 1"},
    {0x00D3, T::u32, "error code history 2"},
    {0x00D4, T::u32, "error code history 3"},
    {0x00D5, T::u32, "error code history 4"},
    {0x00E1, T::u8, "status 2 A1"},
    {0x00E2, T::u8, "status 2 A2"},
    {0x00E3, T::u8, "status 2 A3"},
    {0x00E4, T::u8, "status 2 A4"},
    {0x00E5, T::u8, "status 2 A5"},
    {0x00E6, T::u8, "status 2 A6"},
    {0x00F1, T::u16, "speed A1"},
    {0x00F2, T::u16, "speed A2"},
    {0x00F3, T::u16, "speed A3"},
    {0x00F4, T::u16, "speed A4"},
    {0x00F5, T::u16, "speed A5"},
    {0x00F6, T::u16, "speed A6"},
    {0x0100, T::u8, "battery/mains"},
    {0x0110, T::u8, "binary outputs"},
    {0x0120, T::u8, "hand switch LEDs"},
    {0x0130, T::u8, "locking box LEDs"},
    {0x0140, T::u8, "buzzer"},
    {0x0150, T::u8, "sensor supply"},
    {0x0162, T::u16, "lock status"},
    {0x0164, T::u16, "battery voltage"},
    {0x0165, T::u8, "locking box detected"},
    {0x0166, T::u8, "user"},
    {0x0171, T::u8, "status 1 A1"},
    {0x0172, T::u8, "status 1 A2"},
    {0x0173, T::u8, "status 1 A3"},
    {0x0174, T::u8, "status 1 A4"},
    {0x0175, T::u8, "status 1 A5"},
    {0x0176, T::u8, "status 1 A6"},
    {0x1011, T::f32, "conversion factor A1"},
    {0x1012, T::f32, "conversion factor A2"},
    {0x1013, T::f32, "conversion factor A3"},
    {0x1014, T::f32, "conversion factor A4"},
    {0x1015, T::f32, "conversion factor A5"},
    {0x1016, T::f32, "conversion factor A6"},
    {0x2001, T::user_positions, "user positions A1"},
    {0x2002, T::user_positions, "user positions A2"},
    {0x2003, T::user_positions, "user positions A3"},
    {0x2004, T::user_positions, "user positions A4"},
    {0x2005, T::user_positions, "user positions A5"},
    {0x2006, T::user_positions, "user positions A6"},
    {0x3001, T::cyclic_object, "cyclic object 1"},
    {0x3002, T::cyclic_object, "cyclic object 2"},
    {0x3003, T::cyclic_object, "cyclic object 3"},
    {0x3004, T::cyclic_object, "cyclic object 4"},
    {0x3005, T::cyclic_object, "cyclic object 5"},
    {0x3011, T::u16, "remote speed F1"},
    {0x3012, T::u16, "remote speed F2"},
    {0x3013, T::u16, "remote speed F3"},
    {0x3014, T::u16, "remote speed F4"},
    {0x3015, T::u16, "remote speed F5"},
    {0x3016, T::u16, "remote speed F6"},
    {0x3017, T::u16, "remote speed F7"},
    {0x3018, T::u16, "remote speed F8"},
    {0x3019, T::u16, "remote speed F9"},
    {0x301A, T::u16, "remote speed F10"},
    {0x3021, T::i32, "remote position A1"},
    {0x3022, T::i32, "remote position A2"},
    {0x3023, T::i32, "remote position A3"},
    {0x3024, T::i32, "remote position A4"},
    {0x3025, T::i32, "remote position A5"},
    {0x3026, T::i32, "remote position A6"},
});

constexpr bool sorted() {
  for (std::size_t i = 1; i < kElements.size(); ++i)
    if (kElements[i - 1].id >= kElements[i].id) return false;
  return true;
}
static_assert(sorted(), "the data list must be sorted by ID");

}  // namespace

std::size_t size_of(DataType t) noexcept {
  switch (t) {
    case DataType::u8:
      return 1;
    case DataType::u16:
      return 2;
    case DataType::u32:
    case DataType::i32:
    case DataType::f32:
      return 4;
    case DataType::string31:
      return 31;
    case DataType::string36:
      return 36;
    case DataType::cyclic_object:
      return 24;
    case DataType::user_positions:
      return 26 * 4;
  }
  return 0;
}

const DataElement* find_element(std::uint16_t id) noexcept {
  const auto it = std::ranges::lower_bound(kElements, id, {}, &DataElement::id);
  return it != kElements.end() && it->id == id ? &*it : nullptr;
}

std::span<const DataElement> elements_of(std::uint16_t id) noexcept {
  const std::span<const DataElement> all(kElements);
  const auto first = std::ranges::lower_bound(kElements, id, {}, &DataElement::id);
  const auto index = static_cast<std::size_t>(first - kElements.begin());
  if (first != kElements.end() && first->id == id) return all.subspan(index, 1);
  if ((id & 0x000Fu) != 0) return {};
  std::size_t n = 0;
  while (index + n < all.size() && (all[index + n].id & 0xFFF0u) == id) ++n;
  return all.subspan(index, n);
}

std::size_t value_size(std::uint16_t id) noexcept {
  std::size_t n = 0;
  for (const auto& e : elements_of(id)) n += size_of(e.type);
  return n;
}

}  // namespace cellctl::scu
