#include "runtime/cell_look.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "loop/control_stages.hpp"
#include "loop/loop.hpp"
#include "runtime/cell_parts.hpp"
#include "runtime/cell_view.hpp"
#include "runtime/home_record_file.hpp"
#include "runtime/safe_stop.hpp"
#include "supervisor/cell_sample.hpp"

namespace cellctl::runtime {
namespace {

// Every device has answered since its activation: its link up with a good reply; the SCU with its
// positions (remote mode open: its keep-alive's replies carry them) and its initialised bits; the
// encoder in data exchange.
bool answered(const cell::CellState& s, const CellDevices& devices) noexcept {
  for (const auto* d : devices.devices()) {
    const auto& l = s.links[d->slot()];
    if (!l.active || l.counts.good_replies == 0) return false;
  }
  if (!s.devices[cell::slot(cell::Device::scu)].empty() && !(s.scu_remote && s.scu_status2_known))
    return false;
  return s.devices[cell::slot(cell::Device::encoder)].empty() || s.encoder.data_exchange;
}

// "x 40.0 mm, y 12.5 mm; encoder 40.0012 mm; spindle 0 Hz" and the devices that did not answer.
std::string words_of(const config::CellConfig& cell, const cell::CellState& s, bool all) {
  std::string w;
  for (std::size_t i = 0; i < s.axis_count && i < cell.axes.size(); ++i)
    if (s.axes[i].present)
      w += fmt::format("{}{} {:.1f} mm", w.empty() ? "" : ", ", cell.axes[i].name, s.axes[i].scu_mm);
  for (std::size_t i = 0; i < s.axis_count; ++i)
    if (s.axes[i].measured) w += fmt::format("; encoder {:.4f} mm", s.axes[i].encoder_mm);
  if (!s.devices[cell::slot(cell::Device::spindle)].empty())
    w += fmt::format("; spindle {:.0f} Hz", s.spindle.actual_hz);
  if (all) return w;
  std::string silent;
  for (std::size_t d = 0; d < cell::kMaxDevices; ++d)
    if (!s.devices[d].empty() && (!s.links[d].active || s.links[d].counts.good_replies == 0))
      silent += fmt::format("{}{}", silent.empty() ? "" : ", ", s.devices[d]);
  return fmt::format("{}{}not every device answered{}", w, w.empty() ? "" : "; ",
                     silent.empty() ? std::string() : " (silent: " + silent + ")");
}

}  // namespace

CellLook look_at_cell(const config::CellConfig& cell, LookOptions options) {
  link::MonotonicClock real_clock;
  link::VirtualClock virtual_clock;
  const auto& clock = run_clock(options.mode, real_clock, virtual_clock);
  auto parts = open_cell_parts(cell, options.mode, clock, virtual_clock, options.trace, {}, options.emulators,
                               options.device_kinds);
  const auto home = runtime::load_home_record(
      runtime::home_record_path(
          options.state_dir.empty() ? cell.state_dir : options.state_dir,
          options.mode == RunMode::hardware ? std::string_view{} : std::string_view{to_string(options.mode)}),
      cell, config_sha256(cell));
  loop::Loop loop(clock, *parts.waiter, link::milliseconds(cell.loop.period_ms), loop::kControlStages,
                  &real_clock);
  std::atomic<bool> emulators_stop{false};
  std::thread emulators;
  if (parts.emulated && options.mode != RunMode::virtual_time)
    emulators = std::thread([&] { serve_emulators(emulators_stop, real_clock, nullptr, *parts.emulated); });

  CellLook look;
  cell::CellState state;
  state.axis_count = static_cast<std::uint8_t>(cell.axes.size());
  const auto start = clock.now();
  const auto seconds = [](double s) {
    return std::chrono::duration_cast<link::Duration>(std::chrono::duration<double>(s));
  };
  const auto bound = seconds(options.answer_within_s);
  SafeStop rest(*parts.devices, seconds(options.shutdown_timeout_s), start);
  std::atomic<bool> stop{false};
  bool read = false;
  parts.devices->activate(start);
  loop.run(
      [&](link::TimePoint now, std::uint64_t) {
        if (parts.emulated && options.mode == RunMode::virtual_time) parts.emulated->poll(now);
        parts.devices->receive(now);
        parts.devices->read(now, state);
        rest.observe(now, state);
        if (!read && (answered(state, *parts.devices) || now - start > bound)) {
          read = true;
          look.answered = answered(state, *parts.devices);
          look.view.t = link::to_seconds(now - start);
          show_cell(state, home, *parts.devices, look.view);
          look.sample = supervisor::cell_sample(state);
          look.words = words_of(cell, state, look.answered);
          rest.begin(now);  // read: every device to rest and closed, as at a run's end
        }
        if (read) rest.step(now, false);
        parts.devices->transmit(now);
        if (read && rest.done()) stop.store(true);
      },
      stop);
  emulators_stop.store(true);
  if (emulators.joinable()) emulators.join();
  // Said loudly, as after a job (the scheduler blocks no start for it: the look started nothing, and
  // the first job's own start-up and stop judge the device again).
  for (const auto& v : rest.verdicts())
    if (v && v->safe == Safe::unknown)
      look.words += fmt::format("; {} safe state UNKNOWN: {}", v->device, v->evidence);
  return look;
}

}  // namespace cellctl::runtime
