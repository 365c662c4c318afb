#pragma once
// One fault to rehearse, as `cellctl run --fault DEVICE:KIND@T[+D]` gives it: which device, what goes
// wrong, T seconds after the run starts, for D seconds (for ever without). KIND is a fault on the
// line (silent, disconnect, corrupt, garbage, delay=MS: a link::LinkFault) or `error`: the device
// reports a fault of its own as its manual describes it (see FaultRehearsal).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "device_seam/device_registry.hpp"
#include "link/clock.hpp"
#include "link/link_fault.hpp"

namespace cellctl::runtime {

struct FaultSpec {
  std::string device;                   // its kind's name (device_seam/device_registry.hpp)
  std::optional<link::LinkFault> line;  // nullopt: the device's own error
  link::Duration at{};                  // after the run starts
  std::optional<link::Duration> lasting;
  std::string text;  // as given: names the fault in the journal and in messages

  // "silent", …, "delay", "error".
  [[nodiscard]] std::string_view kind_name() const noexcept {
    return line ? link::to_string(line->kind) : std::string_view("error");
  }
};

struct FaultSpecError {
  std::string reason;  // what is wrong and what is expected, without the text itself
};

// The grammar and its limits: DEVICE is a kind of `kinds` (scu, spindle, encoder); KIND ∈ {silent,
// disconnect, corrupt, garbage, delay=MS (0 < MS ≤ 60000), error}; T ≥ 0 and 0 < D, in seconds (decimals
// allowed, at most a day).
[[nodiscard]] std::variant<FaultSpec, FaultSpecError> parse_fault_spec(
    std::string_view text, std::span<const device_seam::DeviceKind> kinds = device_seam::cell_device_kinds());

}  // namespace cellctl::runtime
