#pragma once
// One line of the run record as the plant link needs it: fixed size and trivially copyable, so that
// the journal's writer thread hands it to the link's thread through a lock-free queue
// (wire::SpscQueue) without allocating and without waiting on the network.

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>

#include "journal/event.hpp"

namespace cellctl::plant_link {

struct RunEvent {
  enum class Kind : std::uint8_t {
    run_started,    // name: recipe, other: mode, step: steps
    state,          // name: to, other: from, text: reason
    step_started,   // step (1-based), name: label
    step_done,      // step, name: label
    step_failed,    // step, name: label, text: detail
    command,        // name: command, other: source
    fault,          // name: rule, category, text: detail
    fault_cleared,  // name: rule
    sample,         // axes, planned/scu/encoder, spindle
    note,           // text
    run_ended,      // name: outcome
  };
  Kind kind = Kind::note;
  double t = 0.0;
  journal::Text name;
  journal::Text other;
  journal::Text text;
  std::uint32_t step = 0;
  std::uint8_t category = 0;
  std::uint8_t axes = 0;
  std::array<float, journal::kMaxAxes> planned_mm{};
  std::array<float, journal::kMaxAxes> scu_mm{};
  float encoder_mm = 0.0f;
  float spindle_set_hz = 0.0f;
  float spindle_hz = 0.0f;
};

// The event a journal line (journal/event_json.cpp's shape) is, or nullopt for lines the plant does
// not read (the record header, injected faults, the summary).
[[nodiscard]] std::optional<RunEvent> run_event_of(const nlohmann::json& line);

}  // namespace cellctl::plant_link
