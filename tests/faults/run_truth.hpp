#pragma once
// What a finished rehearsal run amounted to, from the two places that know: the emulated plant (is
// anything still moving — the truth behind what cellctl says) and the run's journal (its lines, the
// closing summary, and the summary's `devices` object: per device `safe` ∈ observed | bounded |
// unknown with the evidence in words). Shared by the fault matrix and the soak.

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cell/cell_state.hpp"
#include "runtime/emulated_cell.hpp"

namespace cellctl::faults {

inline constexpr std::array kDevices = {cell::Device::scu, cell::Device::spindle, cell::Device::encoder};

enum class Safe : std::uint8_t { observed, bounded, unknown };
[[nodiscard]] std::string_view to_string(Safe s) noexcept;

// The summary's devices object, per device in cell::Device order (none: absent or not one of the three
// words).
struct DeviceSafety {
  bool present = false;  // the summary has a devices object at all
  std::array<std::optional<Safe>, cell::kDevices> safe{};
  std::array<std::string, cell::kDevices> evidence{};
};
[[nodiscard]] DeviceSafety device_safety(const nlohmann::json& summary);

// Every line of a journal.jsonl that parses; the summary is the last one when the journal was closed.
[[nodiscard]] std::vector<nlohmann::json> read_journal(const std::filesystem::path& file);
// The closing summary line, or null.
[[nodiscard]] nlohmann::json summary_of(const std::vector<nlohmann::json>& journal);

// Whether the emulated spindle motor turns / any emulated actuator moves, right now.
[[nodiscard]] bool spindle_turning(runtime::EmulatedCell& plant);
[[nodiscard]] bool axes_moving(runtime::EmulatedCell& plant);

}  // namespace cellctl::faults
