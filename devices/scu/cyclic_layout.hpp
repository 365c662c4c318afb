#pragma once
// What the session puts in CyclicObj 1 so that ONE RC round trip refreshes position and status of every
// configured actuator plus the error word. A cyclic object has only six read IDs, so:
//   up to 4 actuators:  0x0011.. (one INT32 per configured actuator), 0x0170 (status 1 of all six),
//                       0x00D1 (latest error word)
//   5 or 6 actuators:   0x0010 (all six positions), 0x0170, 0x00D1
// The group IDs cost a few unused bytes but keep it to one telegram; no write data is used.

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>
#include <span>

#include "scu/protocol.hpp"
#include "scu/status_flags.hpp"

namespace cellctl::scu {

struct CyclicRefresh {
  std::array<std::int32_t, kActuatorCount> positions{};  // [a-1]; 0 for actuators not in the layout
  std::array<Status1, kActuatorCount> status{};
  ErrorWord errors;
};

class CyclicLayout {
 public:
  explicit CyclicLayout(std::bitset<kActuatorCount> actuators) noexcept;

  // The CyclicObj value (UINT16[12], little-endian) for RT 0x3001.
  [[nodiscard]] std::array<std::uint8_t, 24> object_value() const noexcept;
  // Bytes of read data one RC reply carries.
  [[nodiscard]] std::size_t read_size() const noexcept { return read_size_; }
  // False (and `out` untouched) when the data does not have the layout's size.
  [[nodiscard]] bool decode(std::span<const std::uint8_t> data, CyclicRefresh& out) const noexcept;

 private:
  std::bitset<kActuatorCount> actuators_;
  bool grouped_positions_;
  std::array<std::uint16_t, 6> read_ids_{};
  std::size_t read_size_ = 0;
};

}  // namespace cellctl::scu
