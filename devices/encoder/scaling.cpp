#include "encoder/scaling.hpp"

#include <algorithm>

namespace cellctl::encoder {

Scaling::Scaling(const EncoderParameters& p, const PhysicalResolution& phys) noexcept
    : steps_(std::max<std::uint64_t>(phys.steps_per_revolution, 1)),
      total_(std::max<std::uint64_t>(phys.total(), 1)) {
  range_ = total_;
  // Class 1 has no scaling, and with scaling off "the values of the scaling parameters are ignored".
  if (p.functionality == Functionality::class1 || !p.scaling) return;
  units_ = std::max<std::uint64_t>(p.measuring_units, 1);
  if (p.functionality == Functionality::class2 || p.units_select == UnitsSelect::per_revolution) {
    mode_ = Mode::per_revolution;
    impulses_ = steps_;
    range_ = std::max<std::uint64_t>(p.total_range, 1);
  } else if (p.units_select == UnitsSelect::per_total_range) {
    mode_ = Mode::per_total_range;
    impulses_ = total_;
    range_ = units_;
  } else {
    mode_ = Mode::per_physical_impulses;
    impulses_ = std::max<std::uint64_t>(p.physical_impulses, 1);
    range_ = std::max<std::uint64_t>(total_ * units_ / impulses_, 1);
  }
}

double Scaling::units_per_revolution() const noexcept {
  if (mode_ == Mode::unscaled) return static_cast<double>(steps_);
  return static_cast<double>(steps_) * static_cast<double>(units_) / static_cast<double>(impulses_);
}

std::uint64_t Scaling::to_units(std::uint64_t physical) const noexcept {
  if (mode_ == Mode::unscaled) return physical % range_;
  // 2^31 × 2^31 fits in 64 bits: physical < 2^31 and units ≤ 2^31 by the parameter rules.
  return (physical * units_ / impulses_) % range_;
}

double units_per_mm(double counts_per_mm, double mm_per_revolution, const Scaling& scaling) noexcept {
  if (counts_per_mm > 0.0) return counts_per_mm;
  if (mm_per_revolution > 0.0) return scaling.units_per_revolution() / mm_per_revolution;
  return 0.0;
}

}  // namespace cellctl::encoder
