#include "runtime/fault_spec.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace cellctl::runtime {
namespace {

constexpr double kMaxSeconds = 86400.0;
constexpr double kMaxDelayMs = 60000.0;
constexpr std::string_view kGrammar = "DEVICE:KIND@T[+D], e.g. scu:silent@2+1.5 or spindle:delay=300@4";

// A plain decimal number ("2", "0.5"): no sign, no exponent, nothing after it.
std::optional<double> decimal(std::string_view s) {
  if (s.empty() || s.find_first_not_of("0123456789.") != std::string_view::npos) return std::nullopt;
  double v = 0.0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::fixed);
  if (r.ec != std::errc{} || r.ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

link::Duration seconds(double s) {
  return std::chrono::round<link::Duration>(std::chrono::duration<double>(s));
}

std::string names_of(std::span<const device_seam::DeviceKind> kinds) {
  std::string out;
  for (const auto& k : kinds) out += fmt::format("{}{}", out.empty() ? "" : ", ", k.name);
  return out;
}

// KIND: the line fault, nullopt for `error`; an error text when it is neither.
std::variant<std::optional<link::LinkFault>, FaultSpecError> kind_named(std::string_view s) {
  using link::LinkFaultKind;
  for (const auto k :
       {LinkFaultKind::silent, LinkFaultKind::disconnect, LinkFaultKind::corrupt, LinkFaultKind::garbage})
    if (s == link::to_string(k)) return std::optional(link::LinkFault{k, {}});
  if (s == "error") return std::optional<link::LinkFault>{};
  if (s == "delay") return FaultSpecError{"delay needs its time in milliseconds: delay=MS, e.g. delay=300"};
  if (s.starts_with("delay=")) {
    const auto ms = decimal(s.substr(6));
    if (!ms || *ms <= 0.0 || *ms > kMaxDelayMs)
      return FaultSpecError{
          fmt::format("delay '{}': MS must be a number of milliseconds above 0 and at most {:g}", s.substr(6),
                      kMaxDelayMs)};
    return std::optional(link::LinkFault{LinkFaultKind::delay, link::milliseconds(*ms)});
  }
  return FaultSpecError{
      fmt::format("unknown kind '{}' (silent, disconnect, corrupt, garbage, delay=MS, error)", s)};
}

}  // namespace

std::variant<FaultSpec, FaultSpecError> parse_fault_spec(std::string_view text,
                                                         std::span<const device_seam::DeviceKind> kinds) {
  const auto colon = text.find(':');
  const auto at = text.find('@');
  if (colon == std::string_view::npos || at == std::string_view::npos || at < colon)
    return FaultSpecError{fmt::format("expected {}", kGrammar)};

  FaultSpec spec;
  spec.text = std::string(text);
  const auto device_text = text.substr(0, colon);
  if (!device_seam::find_kind(kinds, device_text))
    return FaultSpecError{fmt::format("unknown device '{}' ({})", device_text, names_of(kinds))};
  spec.device = std::string(device_text);

  auto kind = kind_named(text.substr(colon + 1, at - colon - 1));
  if (auto* e = std::get_if<FaultSpecError>(&kind)) return std::move(*e);
  spec.line = std::get<std::optional<link::LinkFault>>(kind);

  const auto when = text.substr(at + 1);
  const auto plus = when.find('+');
  const auto start_text = when.substr(0, plus);
  const auto start = decimal(start_text);
  if (!start || *start > kMaxSeconds)
    return FaultSpecError{fmt::format(
        "time '{}': T must be the seconds after the run starts, from 0 to {:g} (then +D for how long)",
        start_text, kMaxSeconds)};
  spec.at = seconds(*start);
  if (plus != std::string_view::npos) {
    const auto lasting_text = when.substr(plus + 1);
    const auto lasting = decimal(lasting_text);
    if (!lasting || *lasting <= 0.0 || *lasting > kMaxSeconds)
      return FaultSpecError{fmt::format(
          "duration '{}': D must be seconds above 0 and at most {:g} (leave out +D for a fault that lasts)",
          lasting_text, kMaxSeconds)};
    spec.lasting = seconds(*lasting);
  }
  return spec;
}

}  // namespace cellctl::runtime
