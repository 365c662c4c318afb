#pragma once
// One event of the run as the plant link needs it: fixed size and trivially copyable, so that the
// journal's writer thread hands it to the link's thread through a lock-free queue (wire::SpscQueue)
// without allocating and without waiting on the network. A copy that owns its texts: the event's own
// names are views that live only as long as the run.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "journal/event.hpp"

namespace cellctl::plant_link {

struct RunEvent {
  enum class Kind : std::uint8_t {
    run_started,    // name: recipe, other: mode, text: job (recipe, homing, teach-in), step: steps
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

// The plant's copy of a run's event as the journal records it (journal::EventListener), or nullopt for
// events the plant does not read (injected faults). Times and samples as the journal's line records
// them (schema/journal_line.hpp), so that the plant reads what the run record holds.
[[nodiscard]] std::optional<RunEvent> run_event_of(const journal::Event& e);
// A note, whole (cut to a Text).
[[nodiscard]] RunEvent note_event(double t, std::string_view text);

}  // namespace cellctl::plant_link
