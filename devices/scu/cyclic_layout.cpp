#include "scu/cyclic_layout.hpp"

#include "scu/data_list.hpp"
#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::scu {

CyclicLayout::CyclicLayout(std::bitset<kActuatorCount> actuators) noexcept
    : actuators_(actuators), grouped_positions_(actuators.count() > 4) {
  read_ids_.fill(kUnusedDataId);
  std::size_t n = 0;
  if (grouped_positions_) {
    read_ids_[n++] = data_id::kPositions;
  } else {
    for (int a = 1; a <= kActuatorCount; ++a)
      if (actuators_.test(static_cast<std::size_t>(a - 1))) read_ids_[n++] = data_id::position(a);
  }
  read_ids_[n++] = data_id::kStatus1;
  read_ids_[n++] = data_id::kErrorCode;
  for (auto id : read_ids_)
    if (id != kUnusedDataId) read_size_ += value_size(id);
}

std::array<std::uint8_t, 24> CyclicLayout::object_value() const noexcept {
  std::array<std::uint8_t, 24> out{};
  wire::ByteWriter w(out);
  for (int i = 0; i < 6; ++i) w.le(kUnusedDataId);  // no write data
  for (auto id : read_ids_) w.le(id);
  return out;
}

bool CyclicLayout::decode(std::span<const std::uint8_t> data, CyclicRefresh& out) const noexcept {
  if (data.size() != read_size_) return false;
  wire::ByteReader r(data);
  CyclicRefresh got;
  for (std::size_t a = 0; a < kActuatorCount; ++a) {
    if (grouped_positions_ || actuators_.test(a)) got.positions[a] = r.le<std::int32_t>();
  }
  for (auto& s : got.status) s = Status1::from_byte(r.u8());
  got.errors = ErrorWord(r.le<std::uint32_t>());
  if (!r.ok() || !r.at_end()) return false;
  out = got;
  return true;
}

}  // namespace cellctl::scu
