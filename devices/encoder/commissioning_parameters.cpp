#include "encoder/commissioning_parameters.hpp"

namespace cellctl::encoder {

std::string_view manufacturer_functions_unavailable(const EncoderParameters& p) noexcept {
  if (!is_scancon(p.functionality))
    return "the encoder's functionality has no manufacturer functions (manual 4.4: Scancon 2.1, 2.2 or 3.0)";
  if (p.without_status_bits)
    return "Scancon 3.0 without status bits cannot enter commissioning mode (manual 4.4)";
  return {};
}

EncoderParameters commissioning_parameters(EncoderParameters p) noexcept {
  p.commissioning = true;
  return p;
}

std::string_view teach_in_unavailable(const EncoderParameters& p) noexcept {
  if (auto why = manufacturer_functions_unavailable(p); !why.empty()) return why;
  if (p.lower_limit_enabled || p.upper_limit_enabled)
    return "the encoder's limit switches are in measuring units, which Teach-In changes: remove "
           "lower_limit/upper_limit from the config for the Teach-In and set them again after it";
  return {};
}

EncoderParameters teach_in_parameters(EncoderParameters p, const PhysicalResolution& phys) noexcept {
  p.commissioning = true;
  p.scaling = true;
  p.units_select = UnitsSelect::per_total_range;
  p.measuring_units = static_cast<std::uint32_t>(phys.total());
  return p;
}

EncoderParameters taught_parameters(EncoderParameters p, std::uint32_t total_resolution) noexcept {
  p.scaling = true;
  p.units_select = UnitsSelect::per_total_range;
  p.measuring_units = total_resolution;
  return p;
}

double teach_in_units_per_mm(double steps_per_mm) noexcept {
  if (steps_per_mm < 1.0) return 0.0;
  double u = 1.0;
  while (u * 10.0 <= steps_per_mm) u *= 10.0;
  return u;
}

}  // namespace cellctl::encoder
