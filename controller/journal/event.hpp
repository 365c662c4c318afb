#pragma once
// What the run record records. Events are small fixed-size values so that the control cycle can
// hand them to the journal without allocating: names are views of strings that outlive the run
// (state names, program labels), free text goes into a fixed buffer.

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <string_view>
#include <variant>

namespace cellctl::journal {

inline constexpr std::size_t kMaxAxes = 6;

// Fixed-capacity text, formatted in place: fmt::format_to_n never allocates and never overflows.
// The capacity holds every message the program composes whole (issue 22: a 160-octet text cut the
// advice off refusals and faults): a message template renders at most kLongestMessage octets at its
// longest arguments, a text that wraps another adds at most kLongestWrapping, and three such layers
// still fit. tests/journal/message_length_test.cpp walks every template in the sources to hold this.
struct Text {
  static constexpr std::size_t kLongestMessage = 480;
  static constexpr std::size_t kLongestWrapping = 160;
  static constexpr std::size_t kCapacity = 1022;  // with `size`, 1 KiB
  static_assert(kLongestMessage + 3 * kLongestWrapping <= kCapacity);

  std::array<char, kCapacity> chars{};
  std::uint16_t size = 0;

  template <class... Args>
  static Text format(fmt::format_string<Args...> f, Args&&... args) {
    Text t;
    const auto r = fmt::format_to_n(t.chars.data(), t.chars.size(), f, std::forward<Args>(args)...);
    t.size = static_cast<std::uint16_t>(std::min<std::size_t>(r.size, t.chars.size()));
    return t;
  }
  [[nodiscard]] std::string_view view() const noexcept { return {chars.data(), size}; }
};

struct RunStarted {
  std::string_view recipe;
  std::string_view cell;
  std::string_view mode;  // "virtual-time", "emulated", "hardware"
  std::uint32_t steps = 0;
  // What the run is for: "recipe" (production), "homing" or "teach-in". Only recipes produce: the plant
  // counts them (plant_link/cell_mirror.hpp). Not in the journal's line (the record's steps say it).
  std::string_view job = "recipe";
};
struct StateChanged {
  std::string_view from;
  std::string_view to;
  Text reason;
};
struct StepStarted {
  std::uint32_t index = 0;
  std::string_view label;
};
struct StepEnded {
  std::uint32_t index = 0;
  std::string_view label;
  bool ok = true;
  Text detail;
};
struct Command {
  std::string_view name;  // start, hold, unhold, stop, abort, reset, clear
  Text source;            // who commanded: "terminal", "web 10.0.0.7:51234 (token …)", "plant …"
};
struct Fault {
  std::string_view rule;
  std::uint8_t category = 1;  // stop category 0/1/2
  Text detail;
};
struct FaultCleared {
  std::string_view rule;
};
struct Sample {
  std::uint8_t axes = 0;
  std::array<float, kMaxAxes> planned_mm{};
  std::array<float, kMaxAxes> scu_mm{};
  float encoder_mm = 0.0f;
  float encoder_mm_s = 0.0f;
  float spindle_set_hz = 0.0f;
  float spindle_actual_hz = 0.0f;
};
// Free text of any length: a note longer than a Text travels as several Note events, every one but the
// last `continued`, and the journal writes them as one note (post_note() in event_sink.hpp).
struct Note {
  Text text;
  bool continued = false;
};
// A fault put in place on purpose (cellctl run --fault), when it begins and when it ends.
struct InjectedFault {
  std::string_view device;  // scu, spindle, encoder
  std::string_view kind;    // silent, disconnect, corrupt, garbage, delay, error
  std::string_view spec;    // as the operator wrote it, e.g. "scu:silent@2+1"
  std::string_view what;    // what the fault does, in words
  bool ended = false;
  bool still_active = false;  // ended: only because the run ended while the fault was in place
};
struct RunEnded {
  std::string_view outcome;  // complete, stopped, aborted
};

using Payload = std::variant<RunStarted, StateChanged, StepStarted, StepEnded, Command, Fault, FaultCleared,
                             Sample, Note, InjectedFault, RunEnded>;

struct Event {
  double t = 0.0;  // seconds since the run started (the loop's clock: real or virtual)
  Payload payload;
};

}  // namespace cellctl::journal
