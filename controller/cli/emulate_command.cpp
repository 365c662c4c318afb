#include "cli/emulate_command.hpp"

#include <fmt/format.h>

#include <memory>
#include <thread>

#include "cli/drive.hpp"
#include "cli/publish_lock.hpp"
#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "link/clock.hpp"
#include "link/pty_pair.hpp"
#include "link/tracing_link.hpp"
#include "runtime/dry_run_state.hpp"
#include "runtime/emulated_cell.hpp"

namespace cellctl::cli {
namespace {

int run_emulate(const GlobalOptions& global, bool power_cycle) {
  const auto cell = device_seam::load_cell_config(global.config);
  // Every path is locked before any link is published, so a refused emulation publishes nothing;
  // declared before the pseudo-terminals, each lock is held until its link has been removed.
  std::vector<std::unique_ptr<PublishLock>> locks;
  const auto kinds = device_seam::cell_device_kinds();
  for (const auto& kind : kinds)
    if (const auto port = kind.port(cell)) locks.push_back(std::make_unique<PublishLock>(port->publish_as));
  std::vector<std::unique_ptr<link::PtyPair>> ptys;
  link::MonotonicClock clock;
  // --trace: every telegram the emulators receive (RX) and send (TX), seen from the devices' side.
  link::LogTraceSink trace_sink;
  std::vector<std::unique_ptr<link::TracingLink>> traced;
  runtime::DeviceLinks links{};
  const auto publish = [&](std::string_view kind, const config::PortConfig& port, link::Link*& side) {
    const std::string name(kind);
    auto& pty = *ptys.emplace_back(std::make_unique<link::PtyPair>(name, port.publish_as));
    side = &pty.device();
    if (global.trace)
      side = traced.emplace_back(std::make_unique<link::TracingLink>(*side, clock, trace_sink, name)).get();
    fmt::print("{:<8} {} (also {}), {}\n", name, pty.peer_path(), port.publish_as, port.line.describe());
  };
  fmt::print("cellctl: emulating cell '{}' from {}\n", cell.name, global.config);
  for (std::size_t slot = 0; slot < kinds.size(); ++slot)
    if (const auto port = kinds[slot].port(cell)) publish(kinds[slot].name, *port, links[slot]);
  // The emulated cell stays powered between emulations, as the dry runs' plant (one per state folder).
  const auto setup = runtime::dry_run_emulator_setup(cell, cell.state_dir, power_cycle);
  fmt::print("plant    {}{}\n", setup.plant_state_file.string(),
             power_cycle ? " (after a power cycle: no actuator initialised)" : "");
  runtime::EmulatedCell emulated(cell, setup, links);
  fmt::print("Ctrl-C ends the emulation.\n");
  std::fflush(stdout);

  while (!g_interrupted.load() && !g_terminated.load()) {
    emulated.poll(clock.now());
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  fmt::print("cellctl: emulation ended\n");
  return kExitOk;
}

}  // namespace

void add_emulate_command(CLI::App& app, Commands& commands) {
  auto* sub = app.add_subcommand("emulate",
                                 "Run the cell's devices as emulators on pseudo-terminals (published at each "
                                 "device's publish_as) until Ctrl-C; refuses a publish_as another live "
                                 "emulation holds");
  sub->footer(
      "The emulated plant keeps its state between emulations and dry runs, as a powered cell does: the\n"
      "SCU's actuator positions and initialised bits and the spindle's hours in "
      "<state_dir>/plant.dry-run.json,\n"
      "the encoder's EEPROM in encoder.emulator.state_file (else <state_dir>/encoder.dry-run.eeprom).\n"
      "--power-cycle starts it as after a power loss: the rods where they were, no actuator initialised\n"
      "(a recipe's `require: homed` then refuses until the axes are homed again).");
  auto power_cycle = std::make_shared<bool>(false);
  sub->add_flag("--power-cycle", *power_cycle,
                "Start the emulated cell as after a power loss (no SCU actuator initialised)");
  commands.on(sub, [&commands, power_cycle] { return run_emulate(commands.global, *power_cycle); });
}

}  // namespace cellctl::cli
