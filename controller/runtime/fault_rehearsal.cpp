#include "runtime/fault_rehearsal.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace cellctl::runtime {
namespace {

// The slot of the kind named `name`, kinds.size() when none is.
std::size_t slot_of(std::span<const device_seam::DeviceKind> kinds, std::string_view name) noexcept {
  const auto* kind = device_seam::find_kind(kinds, name);
  return kind ? static_cast<std::size_t>(kind - kinds.data()) : kinds.size();
}

}  // namespace

std::optional<std::string> FaultRehearsal::problem(const std::vector<FaultSpec>& faults,
                                                   const config::CellConfig& cell,
                                                   std::span<const device_seam::DeviceKind> kinds) {
  std::array<std::size_t, cell::kMaxDevices> line_faults{};
  for (const auto& f : faults) {
    const auto slot = slot_of(kinds, f.device);
    if (slot == kinds.size() || !kinds[slot].port(cell))
      return fmt::format("--fault {}: the cell '{}' has no {}", f.text, cell.name, f.device);
    if (f.line && ++line_faults[slot] > link::FaultInjectingLink::kMaxWindows)
      return fmt::format("--fault {}: at most {} line faults per device", f.text,
                         link::FaultInjectingLink::kMaxWindows);
  }
  return std::nullopt;
}

FaultRehearsal::FaultRehearsal(std::vector<FaultSpec> faults, const config::CellConfig& cell,
                               std::span<const device_seam::DeviceKind> kinds)
    : kinds_(kinds),
      faults_(std::move(faults)),
      began_(faults_.size(), false),
      ended_(faults_.size(), false) {
  if (auto p = problem(faults_, cell, kinds_)) throw std::invalid_argument(*p);
  for (const auto& f : faults_) slots_.push_back(slot_of(kinds_, f.device));
}

std::bitset<cell::kMaxDevices> FaultRehearsal::lines() const noexcept {
  std::bitset<cell::kMaxDevices> out;
  for (std::size_t i = 0; i < faults_.size(); ++i)
    if (faults_[i].line) out.set(slots_[i]);
  return out;
}

void FaultRehearsal::start(link::TimePoint start, const FaultLinks& links) {
  start_ = start;
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    const auto& f = faults_[i];
    if (!f.line) continue;
    auto* l = links[slots_[i]];
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
  std::array<bool, cell::kMaxDevices> wanted{};
  for (std::size_t i = 0; i < faults_.size(); ++i)
    if (!faults_[i].line && open_at(i, now)) wanted[slots_[i]] = true;
  for (std::size_t slot = 0; slot < kinds_.size(); ++slot) {
    if (wanted[slot] == device_error_on_[slot]) continue;
    device_error_on_[slot] = wanted[slot];
    if (auto* emulator = emulators.device(slot)) emulator->set_own_error(wanted[slot]);
  }
}

void FaultRehearsal::post_journal(link::TimePoint now, double t, journal::EventSink& journal) {
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    const auto& f = faults_[i];
    const auto event = [&](bool ended) {
      return journal::InjectedFault{kinds_[slots_[i]].name, f.kind_name(), f.text, what(f, kinds_), ended};
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
      journal.post(t, journal::InjectedFault{kinds_[slots_[i]].name, f.kind_name(), f.text, what(f, kinds_),
                                             true, true});
    }
  }
}

std::string_view FaultRehearsal::what(const FaultSpec& f,
                                      std::span<const device_seam::DeviceKind> kinds) noexcept {
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
  const auto* kind = device_seam::find_kind(kinds, f.device);
  return kind ? kind->own_error : std::string_view("?");
}

}  // namespace cellctl::runtime
