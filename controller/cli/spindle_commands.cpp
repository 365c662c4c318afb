#include "cli/spindle_commands.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "cli/commissioning.hpp"
#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "spindle/fault_numbers.hpp"
#include "spindle/session.hpp"

namespace cellctl::cli {
namespace {

using namespace std::chrono_literals;

enum class SpindleAction { status, start, stop, set, reset };

struct SpindleOptions : DeviceOptions {
  SpindleOptions() { timeout_s = 30.0; }
  double frequency_hz = 0.0;
  std::string direction = "cw";
};

std::string describe_state(const spindle::Snapshot& s) {
  if (s.state == spindle::DeviceState::none) return "ok";
  const auto meaning = spindle::explain_fault_number(s.error_number);
  return fmt::format("{} {}{}{}", s.fault() ? "FAULT" : "warning", s.error_number,
                     meaning.empty() ? "" : ": ", meaning);
}

void print_snapshot(const spindle::Snapshot& s) {
  fmt::print("state          {}\n", describe_state(s));
  fmt::print("motion         {}\n", s.at_speed ? "at speed" : s.at_rest ? "at rest" : "changing speed");
  fmt::print("frequency      set {:.0f} Hz, actual {:.0f} Hz\n", s.set_frequency_hz, s.actual_frequency_hz);
  fmt::print("motor          {:.2f} V, {:.2f} A, {:.1f} W (current limit {:.2f} A{})\n", s.motor_voltage_v,
             s.motor_current_a, s.power_w, s.peak_current_a, s.current_limit ? ", ACTIVE" : "");
  fmt::print("DC link        {:.2f} V\n", s.dc_link_voltage_v);
  fmt::print("temperature    {}\n", s.motor_over_temperature ? "PTC OVER-TEMPERATURE" : "ok");
  fmt::print("run time       converter {} h, motor {} h, motor code {}\n", s.converter_hours, s.motor_hours,
             s.motor_code);
  if (const auto& id = s.identification) {
    fmt::print("converter      type {}, firmware 0x{:04x}, serial {}\n", id->converter_type, id->firmware,
               id->serial_number);
    fmt::print("fault history  {} {} {} {} {} (latest first)\n", id->fault_history[0], id->fault_history[1],
               id->fault_history[2], id->fault_history[3], id->fault_history[4]);
  }
}

class SpindleCommissioning {
 public:
  SpindleCommissioning(const GlobalOptions& global, const SpindleOptions& options,
                       const config::SpindleSection& section)
      : options_(options), c_(global, options, section.port, "spindle", section.session) {}

  int run(SpindleAction action) {
    c_.activate();
    const bool up = c_.drive([&] {
      const auto& s = snapshot();
      return session_.lifecycle() == link::Lifecycle::active && s.status_valid && s.values_valid;
    });
    if (!up) return failed_to("reach the converter");
    switch (action) {
      case SpindleAction::status:
        break;
      case SpindleAction::start: {
        const auto dir = options_.direction == "ccw" ? spindle::Direction::counter_clockwise
                                                     : spindle::Direction::clockwise;
        if (!session_.start(options_.frequency_hz, dir)) return refuse("start");
        if (!c_.drive_showing([&] { return snapshot().at_speed || snapshot().start_refused; },
                              [&] {
                                return frequency_progress(
                                    fmt::format("running up to {:.0f} Hz", options_.frequency_hz));
                              }))
          return failed_to("reach speed");
        if (snapshot().start_refused) {
          spdlog::error("start refused: {}", snapshot().start_refused_reason);
          return kExitFailed;
        }
        break;
      }
      case SpindleAction::stop:
        if (!session_.stop()) return refuse("stop");
        if (!c_.drive_showing([&] { return snapshot().at_rest && !session_.commands_pending(); },
                              [&] { return frequency_progress("running down"); }))
          return failed_to("come to rest");
        break;
      case SpindleAction::set:
        if (!session_.set_frequency(options_.frequency_hz)) return refuse("set the frequency");
        if (!c_.drive([&] { return !session_.commands_pending(); }))
          return failed_to("acknowledge the set-point");
        break;
      case SpindleAction::reset:
        if (!session_.reset()) return refuse("reset");
        if (!c_.drive([&] { return !session_.commands_pending(); }))
          return failed_to("acknowledge the reset");
        break;
    }
    // The measured values are polled slower than the flags: wait for a set taken after the command.
    if (action != SpindleAction::status && !c_.drive_for(session_.config().values_poll + 100ms))
      return failed_to("keep answering");
    print_snapshot(snapshot());
    return snapshot().fault() ? kExitFailed : kExitOk;
  }

 private:
  const spindle::Snapshot& snapshot() const { return c_.snapshot(); }
  // The measured frequency is polled every values_poll (250 ms by default): fresh enough for 0.5 s lines.
  std::string frequency_progress(const std::string& phase) const {
    return fmt::format("{}: actual {:.0f} Hz", phase, snapshot().actual_frequency_hz);
  }

  // The command line was checked by the parser: a refusal is the session's state (not active, its
  // command queue full), so the command failed — not a usage error.
  int refuse(const char* what) const {
    return c_.refuse(fmt::format("{} now (not active, or its command queue is full)", what).c_str());
  }

  int failed_to(const char* what) {
    if (g_interrupted.load()) return stop_after_interrupt();
    const int code = c_.failed_to(what);
    if (code == kExitFailed) print_snapshot(snapshot());
    return code;
  }

  // Ctrl-C: bring the spindle to rest before exiting (drive_until ends at once once interrupted).
  int stop_after_interrupt() {
    if (session_.stop()) {
      const auto deadline = c_.clock().now() + 10s;
      while (c_.clock().now() < deadline) {
        c_.step(c_.clock().now());
        if (c_.faulted() || (snapshot().at_rest && !session_.commands_pending())) break;
        std::this_thread::sleep_for(1ms);
      }
    }
    spdlog::warn("interrupted; spindle {}", snapshot().at_rest ? "at rest" : "NOT confirmed at rest");
    return kExitInterrupted;
  }

  const SpindleOptions& options_;
  Commissioning<spindle::Session> c_;
  spindle::Session& session_ = c_.session();
};

int run_spindle(const GlobalOptions& global, const SpindleOptions& options, SpindleAction action) {
  const auto cell = device_seam::load_cell_config(global.config);
  if (!cell.spindle && !options.port) {
    spdlog::error("{} has no spindle: section; add one or give --port", global.config);
    return kExitConfig;
  }
  if (action == SpindleAction::start || action == SpindleAction::set) {
    // The safety monitor stops a run outside this range: commissioning obeys it too, before anything turns.
    const auto& l = cell.limits;
    if (options.frequency_hz < l.spindle_min_hz || options.frequency_hz > l.spindle_max_hz) {
      spdlog::error(
          "spindle {} refused: {:g} Hz is outside the cell's spindle range of {:g} to {:g} Hz "
          "(limits.spindle_min_hz/spindle_max_hz in {}); nothing turned",
          action == SpindleAction::start ? "start" : "set", options.frequency_hz, l.spindle_min_hz,
          l.spindle_max_hz, global.config);
      return kExitUsage;
    }
  }
  SpindleCommissioning commissioning(global, options, cell.spindle.value_or(config::SpindleSection{}));
  return commissioning.run(action);
}

}  // namespace

void add_spindle_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<SpindleOptions>();
  DeviceGroup group(app, "spindle", "Commission the SycoTec spindle converter (RS232)", *options,
                    "Seconds to wait for the converter");

  auto add = [&](const char* name, const char* help, SpindleAction action) {
    auto* sub = group.add_action(name, help);
    commands.on(sub, [&commands, options, action] { return run_spindle(commands.global, *options, action); });
    return sub;
  };
  add("status", "Read and print the converter's status, values and identification", SpindleAction::status);
  auto* start = add("start", "Start the spindle and wait until it is at speed", SpindleAction::start);
  start->add_option("--frequency", options->frequency_hz, "Set-point in Hz")
      ->required()
      ->check(CLI::Range(1.0, 65535.0));
  start->add_option("--direction", options->direction, "cw (Rechtslauf) or ccw (Linkslauf)")
      ->check(CLI::IsMember({"cw", "ccw"}))
      ->capture_default_str();
  add("stop", "Stop the spindle and wait until it is at rest", SpindleAction::stop);
  auto* set =
      add("set", "Change the frequency set-point (takes effect at once while running)", SpindleAction::set);
  set->add_option("--frequency", options->frequency_hz, "Set-point in Hz")
      ->required()
      ->check(CLI::Range(1.0, 65535.0));
  add("reset", "Reset a converter fault (CMD System Reset) and show the result", SpindleAction::reset);
}

}  // namespace cellctl::cli
