#pragma once
// From physical steps to measuring units (manual 4.1.2–4.1.8): per revolution (Class 2, Scancon
// 0b00), per maximum total measuring range (0b01), per physical impulses (0b10), or unscaled. Pure
// integer arithmetic in 64 bits, so emulator and master agree on every count.

#include <cstdint>

#include "encoder/parameters.hpp"

namespace cellctl::encoder {

class Scaling {
 public:
  Scaling(const EncoderParameters& p, const PhysicalResolution& phys) noexcept;

  // Measuring units over the whole range: positions run 0 … range() − 1 and then roll over.
  [[nodiscard]] std::uint64_t range() const noexcept { return range_; }
  // Measuring units per shaft revolution (non-integer with physical impulses).
  [[nodiscard]] double units_per_revolution() const noexcept;
  // A physical position 0 … total − 1 (after the code sequence) in measuring units.
  [[nodiscard]] std::uint64_t to_units(std::uint64_t physical) const noexcept;
  [[nodiscard]] bool scaled() const noexcept { return mode_ != Mode::unscaled; }

 private:
  enum class Mode : std::uint8_t { unscaled, per_revolution, per_total_range, per_physical_impulses };
  Mode mode_ = Mode::unscaled;
  std::uint64_t steps_ = 1;     // physical steps per revolution
  std::uint64_t total_ = 1;     // physical steps over the whole range
  std::uint64_t units_ = 1;     // measuring units (per revolution / desired)
  std::uint64_t impulses_ = 1;  // physical impulses those units correspond to
  std::uint64_t range_ = 1;
};

// Measuring units per mm of the axis: counts_per_mm when given (> 0), else the units per revolution
// over the mm per revolution; 0 when neither is given.
[[nodiscard]] double units_per_mm(double counts_per_mm, double mm_per_revolution,
                                  const Scaling& scaling) noexcept;

}  // namespace cellctl::encoder
