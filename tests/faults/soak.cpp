#include "faults/soak.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>
#include <stdexcept>

#include "emulation/emulator_setup.hpp"
#include "runtime/cell_run.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::faults {
namespace {

constexpr double kRecipeS = 91.0;  // the demo's length: faults and commands fall inside it
// How long a line must have been back before the end for a stop to be confirmed over it: a retry
// (0.1 s), the stop's reply, and the spindle's run-down from 400 Hz at 400 Hz/s (1 s), + 0.4 s.
constexpr double kConfirmS = 1.5;

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
bool chance(std::mt19937_64& rng, double p) {
  return uniform(rng, 0.0, 1.0) < p;
}

supervisor::Command command_of(const std::string& word) {
  if (word == "hold") return supervisor::Command::hold;
  if (word == "unhold") return supervisor::Command::unhold;
  if (word == "stop") return supervisor::Command::stop;
  throw std::invalid_argument("soak: no such operator command: " + word);
}

}  // namespace

SoakPlan soak_plan(std::uint64_t seed, std::uint64_t index) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(index >> 32)};
  std::mt19937_64 rng(seq);
  SoakPlan plan;
  // Up to two faults, on different devices; any kind; at any time of the recipe; a quarter for ever.
  std::vector<cell::Device> devices(kDevices.begin(), kDevices.end());
  std::shuffle(devices.begin(), devices.end(), rng);
  const auto faults = std::uniform_int_distribution<std::size_t>(0, 2)(rng);
  constexpr std::array<const char*, 6> kinds = {"silent",  "disconnect", "corrupt",
                                                "garbage", "delay",      "error"};
  for (std::size_t i = 0; i < faults; ++i) {
    std::string kind = kinds[std::uniform_int_distribution<std::size_t>(0, kinds.size() - 1)(rng)];
    if (kind == "delay") kind += fmt::format("={:.0f}", uniform(rng, 10.0, 600.0));
    std::string text =
        fmt::format("{}:{}@{:.2f}", cell::to_string(devices[i]), kind, uniform(rng, 0.5, kRecipeS));
    if (!chance(rng, 0.25)) text += fmt::format("+{:.2f}", uniform(rng, 0.1, 6.0));
    plan.faults.push_back(std::move(text));
  }
  // Half the runs are held once and let go again; a quarter is stopped by the operator.
  if (chance(rng, 0.5)) {
    const double at = uniform(rng, 2.0, kRecipeS - 5.0);
    plan.commands.push_back({at, "hold"});
    plan.commands.push_back({at + uniform(rng, 0.2, kMaxHoldS), "unhold"});
  }
  if (chance(rng, 0.25)) plan.commands.push_back({uniform(rng, 2.0, kRecipeS), "stop"});
  std::sort(plan.commands.begin(), plan.commands.end(),
            [](const SoakCommand& a, const SoakCommand& b) { return a.at_s < b.at_s; });
  return plan;
}

SoakRun soak_run(const SoakPlan& plan, const config::CellConfig& cell, const recipe::Recipe& recipe,
                 const std::filesystem::path& dir) {
  SoakRun out;
  out.plan = plan;
  const auto fail = [&](std::string s) { out.violations.push_back(std::move(s)); };
  std::filesystem::remove_all(dir);
  const auto wall = std::chrono::steady_clock::now();
  bool axes = false, spindle = false;
  try {
    runtime::RunOptions options;
    options.mode = runtime::RunMode::virtual_time;
    options.journal_dir = dir / "journal";
    for (const auto& text : plan.faults) {
      auto parsed = runtime::parse_fault_spec(text);
      if (const auto* bad = std::get_if<runtime::FaultSpecError>(&parsed))
        throw std::invalid_argument(text + ": " + bad->reason);
      options.faults.push_back(std::get<runtime::FaultSpec>(parsed));
    }
    options.emulators = emulation::load_emulator_setup(cell);
    if (options.emulators->encoder) options.emulators->encoder->state_file = dir / "encoder.eeprom";
    runtime::CellRun run(cell, recipe, std::move(options));

    std::atomic<bool> interrupt{false};
    std::size_t next = 0;
    bool stuck = false;
    run.on_cycle([&](double t, runtime::CellRun& r) {
      // An unhold may come while the hold still brakes the axes: the move resumes from that moving state.
      for (; next < plan.commands.size() && plan.commands[next].at_s <= t; ++next)
        r.request(command_of(plan.commands[next].command));
      if (t > kStuckS && !stuck) {
        stuck = true;
        interrupt.store(true);  // Ctrl-C: the operator stop …
      }
      if (stuck && t > kStuckS + 1.0) interrupt.store(true);  // … and again: the emergency stop
      if (t > kStuckS + 30.0) throw std::runtime_error("the run did not end even when stopped");
    });
    const auto result = run.run(interrupt);
    out.virtual_s = result.duration_s;
    if (stuck) fail(fmt::format("stuck: not ended {:g} s after the start", kStuckS));
    axes = axes_moving(*run.emulators());
    spindle = spindle_turning(*run.emulators());
  } catch (const std::exception& e) {
    fail(std::string("the run failed: ") + e.what());
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();

  const auto journal = read_journal(dir / "journal" / "journal.jsonl");
  // When each device's line was last down (a line fault, not the device's own error, which it reports
  // over a good line); still on at the end counts as down at the end.
  std::array<std::optional<double>, cell::kDevices> line_back_at{};
  for (const auto& j : journal) {
    const auto event = j.value("event", "");
    if (event == "fault_injected") ++out.faults_injected;
    if (event == "fault_injection_ended" && j.value("kind", "") != "error")
      for (const auto d : kDevices)
        if (j.value("device", "") == cell::to_string(d))
          line_back_at[static_cast<std::size_t>(d)] =
              j.value("still_active", false) ? 1e9 : j.value("t", 0.0);
  }
  const auto summary = summary_of(journal);
  if (summary.is_null()) {
    fail("the journal was not closed with a summary");
  } else {
    out.outcome = summary.value("outcome", "");
    out.devices = device_safety(summary);
    if (!out.devices.present) fail("the summary has no devices object");
  }
  for (const auto d : kDevices) {
    const auto i = static_cast<std::size_t>(d);
    const auto& safe = out.devices.safe[i];
    if (out.devices.present && !safe) fail(fmt::format("devices.{}.safe missing", cell::to_string(d)));
    // A stop could have been confirmed when the line was up for kConfirmS before the end.
    const bool could_confirm = !line_back_at[i] || *line_back_at[i] <= out.virtual_s - kConfirmS;
    if (safe == Safe::unknown && could_confirm)
      fail(fmt::format(
          "{} unknown, though its line was up for the last {:g} s (a stop could have been confirmed): {}",
          cell::to_string(d), kConfirmS, out.devices.evidence[i]));
  }
  const auto unknown = [&](cell::Device d) {
    return out.devices.safe[static_cast<std::size_t>(d)] == Safe::unknown;
  };
  if (axes && !unknown(cell::Device::scu))
    fail("an actuator still moves at the end, and the summary does not say so");
  if (spindle && !unknown(cell::Device::spindle))
    fail("the spindle still turns at the end, and the summary does not say so");
  if (out.violations.empty()) std::filesystem::remove_all(dir);
  return out;
}

std::string describe(const SoakRun& run) {
  std::string commands;
  for (const auto& c : run.plan.commands)
    commands += fmt::format("{}{}@{:.2f}", commands.empty() ? "" : " ", c.command, c.at_s);
  std::string safe;
  for (const auto d : kDevices) {
    const auto& s = run.devices.safe[static_cast<std::size_t>(d)];
    safe += fmt::format("{}{} {}", safe.empty() ? "" : ", ", cell::to_string(d), s ? to_string(*s) : "-");
  }
  return fmt::format(
      "faults [{}] commands [{}] → {} after {:.1f} s ({:.2f} s wall); {}; {}",
      fmt::join(run.plan.faults, " "), commands, run.outcome, run.virtual_s, run.wall_s, safe,
      run.violations.empty() ? "ok" : "VIOLATION: " + fmt::format("{}", fmt::join(run.violations, "; ")));
}

}  // namespace cellctl::faults
