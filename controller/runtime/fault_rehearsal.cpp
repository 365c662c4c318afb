#include "runtime/fault_rehearsal.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "encoder/diagnosis.hpp"

namespace cellctl::runtime {
namespace {

std::size_t index(cell::Device d) noexcept {
  return static_cast<std::size_t>(d);
}

bool cell_has(const config::CellConfig& cell, cell::Device d) noexcept {
  switch (d) {
    case cell::Device::scu:
      return cell.scu.has_value();
    case cell::Device::spindle:
      return cell.spindle.has_value();
    case cell::Device::encoder:
      return cell.encoder.has_value();
  }
  return false;
}

void set_device_error(cell::Device d, bool on, EmulatedCell& emulators) {
  switch (d) {
    case cell::Device::scu:
      if (auto* scu = emulators.scu())
        for (int a = 1; a <= scu::kActuatorCount; ++a)
          if (scu->has_actuator(a)) scu->set_actuator_fault(a, on);
      return;
    case cell::Device::spindle:
      if (auto* spindle = emulators.spindle()) spindle->set_over_temperature(on);
      return;
    case cell::Device::encoder:
      if (auto* encoder = emulators.encoder()) encoder->set_alarm(encoder::alarm::position_error, on);
      return;
  }
}

}  // namespace

std::optional<std::string> FaultRehearsal::problem(const std::vector<FaultSpec>& faults,
                                                   const config::CellConfig& cell) {
  std::array<std::size_t, cell::kDevices> line_faults{};
  for (const auto& f : faults) {
    if (!cell_has(cell, f.device))
      return fmt::format("--fault {}: the cell '{}' has no {}", f.text, cell.name, cell::to_string(f.device));
    if (f.line && ++line_faults[index(f.device)] > link::FaultInjectingLink::kMaxWindows)
      return fmt::format("--fault {}: at most {} line faults per device", f.text,
                         link::FaultInjectingLink::kMaxWindows);
  }
  return std::nullopt;
}

FaultRehearsal::FaultRehearsal(std::vector<FaultSpec> faults, const config::CellConfig& cell)
    : faults_(std::move(faults)), began_(faults_.size(), false), ended_(faults_.size(), false) {
  if (auto p = problem(faults_, cell)) throw std::invalid_argument(*p);
}

std::bitset<cell::kDevices> FaultRehearsal::lines() const noexcept {
  std::bitset<cell::kDevices> out;
  for (const auto& f : faults_)
    if (f.line) out.set(index(f.device));
  return out;
}

void FaultRehearsal::start(link::TimePoint start, const FaultLinks& links) {
  start_ = start;
  for (const auto& f : faults_) {
    if (!f.line) continue;
    auto* l = links[index(f.device)];
    if (l == nullptr) throw std::logic_error("fault rehearsal: no fault-injecting link for " + f.text);
    const auto until = f.lasting ? std::optional(start + f.at + *f.lasting) : std::nullopt;
    if (!l->schedule(*f.line, start + f.at, until))
      throw std::logic_error("fault rehearsal: the link's schedule is full at " + f.text);
  }
}

bool FaultRehearsal::open_at(std::size_t i, link::TimePoint now) const noexcept {
  return now >= start_ + faults_[i].at && !over_at(i, now);
}

bool FaultRehearsal::over_at(std::size_t i, link::TimePoint now) const noexcept {
  const auto& f = faults_[i];
  return f.lasting && now >= start_ + f.at + *f.lasting;
}

void FaultRehearsal::drive_emulators(link::TimePoint now, EmulatedCell& emulators) {
  std::array<bool, cell::kDevices> wanted{};
  for (std::size_t i = 0; i < faults_.size(); ++i)
    if (!faults_[i].line && open_at(i, now)) wanted[index(faults_[i].device)] = true;
  for (const auto d : {cell::Device::scu, cell::Device::spindle, cell::Device::encoder}) {
    if (wanted[index(d)] == device_error_on_[index(d)]) continue;
    device_error_on_[index(d)] = wanted[index(d)];
    set_device_error(d, wanted[index(d)], emulators);
  }
}

void FaultRehearsal::post_journal(link::TimePoint now, double t, journal::EventSink& journal) {
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    const auto& f = faults_[i];
    const auto event = [&](bool ended) {
      return journal::InjectedFault{cell::to_string(f.device), f.kind_name(), f.text, what(f), ended};
    };
    if (!began_[i] && now >= start_ + f.at) {
      began_[i] = true;
      journal.post(t, event(false));
    }
    if (began_[i] && !ended_[i] && over_at(i, now)) {
      ended_[i] = true;
      journal.post(t, event(true));
    }
  }
}

void FaultRehearsal::post_run_end(double t, journal::EventSink& journal) {
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    const auto& f = faults_[i];
    if (!began_[i]) {
      journal.post(
          t, journal::Note{journal::Text::format("fault {} was not injected: the run ended first", f.text)});
    } else if (!ended_[i]) {
      ended_[i] = true;
      journal.post(
          t, journal::InjectedFault{cell::to_string(f.device), f.kind_name(), f.text, what(f), true, true});
    }
  }
}

std::string_view FaultRehearsal::what(const FaultSpec& f) noexcept {
  if (f.line) {
    switch (f.line->kind) {
      case link::LinkFaultKind::silent:
        return "the line carries nothing either way";
      case link::LinkFaultKind::disconnect:
        return "the port reports itself gone (EIO), as when its cable is pulled";
      case link::LinkFaultKind::corrupt:
        return "a bit flipped in every 4th byte, both ways: checksums fail";
      case link::LinkFaultKind::garbage:
        return "bursts of random bytes mixed into the traffic, both ways";
      case link::LinkFaultKind::delay:
        return "the device's replies arrive late";
    }
  }
  switch (f.device) {
    case cell::Device::scu:
      return "every actuator reports an actuator fault (error code bits 15..20) and is fast-stopped";
    case cell::Device::spindle:
      return "the converter latches fault 31, motor over-temperature, and runs the motor down";
    case cell::Device::encoder:
      return "the encoder reports the position error alarm in its diagnosis";
  }
  return "?";
}

}  // namespace cellctl::runtime
