#pragma once
// The parameter sets the encoder's manufacturer functions need (manual 4.4), derived from the
// configured ones: the device-specific part of switching the encoder for a commissioning function and
// back. The session sends them with reconfigure() + activate(); nothing here touches the bus.

#include <cstdint>
#include <string_view>

#include "encoder/parameters.hpp"

namespace cellctl::encoder {

// Why the manufacturer functions (direction on the fly, Teach-In) are impossible with this
// functionality at all (4.4: Scancon 2.1/2.2/3.0 with status bits only), or empty.
[[nodiscard]] std::string_view manufacturer_functions_unavailable(const EncoderParameters& p) noexcept;

// `p` in commissioning mode (octet 26 bit 2), what 4.4 asks for direction changes and Teach-In.
[[nodiscard]] EncoderParameters commissioning_parameters(EncoderParameters p) noexcept;

// Why Teach-In is impossible with `p` (beyond the functionality), or empty: its limit switches are
// in measuring units, which Teach-In changes.
[[nodiscard]] std::string_view teach_in_unavailable(const EncoderParameters& p) noexcept;

// 4.4.2.1's prerequisites: commissioning mode, scaling on, desired measuring units per maximum total
// measuring range (0b01) — with one unit per physical step, so positions keep their meaning while
// the encoder is switched. (The offset of 0 is the encoder's own during Teach-In.)
[[nodiscard]] EncoderParameters teach_in_parameters(EncoderParameters p,
                                                    const PhysicalResolution& phys) noexcept;

// After Teach-In: the configured parameters with the total resolution as the desired measuring units
// per maximum total measuring range (4.4.2.1 "End": entered into Maximum Desired Measuring Units).
[[nodiscard]] EncoderParameters taught_parameters(EncoderParameters p,
                                                  std::uint32_t total_resolution) noexcept;

// The unit Teach-In is told the distance in: the largest power of ten per mm not above the physical
// steps per mm, so the total resolution stays within the physical range (4.1.2). 0 below 1 step/mm.
[[nodiscard]] double teach_in_units_per_mm(double steps_per_mm) noexcept;

}  // namespace cellctl::encoder
