#pragma once
// How a device was left at the end of a run — observed at rest, bounded by its own protection, or
// unknown — and what the safe-stop tells every device while it brings the cell to rest.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "link/clock.hpp"

namespace cellctl::device_seam {

enum class Safe : std::uint8_t { observed, bounded, unknown };
[[nodiscard]] constexpr const char* to_string(Safe s) noexcept {
  return s == Safe::observed ? "observed" : s == Safe::bounded ? "bounded" : "unknown";
}

struct DeviceSafety {
  std::string_view device;  // its name (device_seam::CellDevice::name(): static text)
  Safe safe = Safe::unknown;
  std::string evidence;
};

// The safe-stop's view of the run, handed to each device's stop policy at every step.
struct StopContext {
  link::TimePoint start{};                  // the run's start: the evidence's times count from it
  std::optional<link::TimePoint> begun_at;  // the orderly end began; nullopt: a stop during the run
  // How long after the end (or after a loss, during the run) a stop is sent again to a device that
  // has no bound of its own.
  link::Duration confirm_within{};
  bool axes_resolved = false;  // every device that drives the axes is resolved

  [[nodiscard]] double t_of(link::TimePoint p) const noexcept { return link::to_seconds(p - start); }
};

}  // namespace cellctl::device_seam
