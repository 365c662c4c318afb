#include "scu/session_config.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>

#include "link/clock.hpp"

namespace cellctl::scu {

void validate(const SessionConfig& c) {
  if (c.safety_id > 2)
    throw std::invalid_argument("scu session: safety_id must be 0, 1 or 2, got " +
                                std::to_string(c.safety_id));
  if (c.keepalive_period < link::Duration::zero() || c.keepalive_period >= kWatchdogPeriod)
    throw std::invalid_argument(
        "scu session: keepalive_ms must be 0..499 (the SCU watchdog is 500 ms), got " +
        fmt::format("{:.0f}", link::to_milliseconds(c.keepalive_period)));
  if (c.reply_timeout <= link::Duration::zero())
    throw std::invalid_argument("scu session: reply_timeout_ms must be > 0, got " +
                                fmt::format("{:.0f}", link::to_milliseconds(c.reply_timeout)));
  if (c.retries < 0)
    throw std::invalid_argument("scu session: retries must be ≥ 0, got " + std::to_string(c.retries));
  if (c.link_fault_after <= c.reply_timeout)
    throw std::invalid_argument("scu session: link_fault_after_ms must exceed reply_timeout_ms, got " +
                                fmt::format("{:.0f}", link::to_milliseconds(c.link_fault_after)));
  if (c.actuators.none()) throw std::invalid_argument("scu session: no actuator configured");
  for (std::size_t a = 0; a < kActuatorCount; ++a) {
    const auto& spec = c.specs[a];
    if (c.actuators.test(a) &&
        !(spec.edges_per_mm > 0.0 && spec.full_speed_mm_s > 0.0 && spec.stroke_mm > 0.0))
      throw std::invalid_argument(fmt::format(
          "scu session: actuator {} needs edges_per_mm, stroke_mm and full speed > 0, got {:g}, {:g}, {:g}",
          a + 1, spec.edges_per_mm, spec.stroke_mm, spec.full_speed_mm_s));
  }
  for (std::size_t f = 0; f < c.functions.size(); ++f) {
    const auto& fn = c.functions[f];
    if (fn.defined && (fn.actuators & ~c.actuators).any())
      throw std::invalid_argument("scu session: function F" + std::to_string(f + 1) +
                                  " moves an actuator that is not configured");
  }
}

}  // namespace cellctl::scu
