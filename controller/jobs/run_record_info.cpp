#include "jobs/run_record_info.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <chrono>
#include <variant>

namespace cellctl::jobs {
namespace {

struct Device {
  const char* name;
  const config::PortConfig* port;
};

std::vector<Device> devices(const config::CellConfig& cell) {
  std::vector<Device> out;
  if (cell.scu) out.push_back({"scu", &cell.scu->port});
  if (cell.spindle) out.push_back({"spindle", &cell.spindle->port});
  if (cell.encoder) out.push_back({"encoder", &cell.encoder->port});
  return out;
}

struct StepKind {
  journal::RecordStep operator()(const recipe::Move&) const { return {{}, "move", std::nullopt}; }
  journal::RecordStep operator()(const recipe::Spindle&) const { return {{}, "spindle", std::nullopt}; }
  journal::RecordStep operator()(const recipe::Dwell& d) const { return {{}, "dwell", d.seconds}; }
  journal::RecordStep operator()(const recipe::Wait&) const { return {{}, "wait", std::nullopt}; }
  journal::RecordStep operator()(const recipe::Require&) const { return {{}, "require", 0.0}; }
  journal::RecordStep operator()(const recipe::Home&) const { return {{}, "home", std::nullopt}; }
  journal::RecordStep operator()(const recipe::TeachIn&) const { return {{}, "teach-in", std::nullopt}; }
};

}  // namespace

std::string mode_label(const config::CellConfig& cell, runtime::RunMode mode) {
  if (mode == runtime::RunMode::virtual_time) return "virtual time (every device emulated, simulated lines)";
  if (mode == runtime::RunMode::emulated) return "emulated (every device on its emulator, in this process)";
  std::vector<std::string> emulated;
  const auto all = devices(cell);
  for (const auto& d : all)
    if (d.port->emulated()) emulated.emplace_back(d.name);
  if (!all.empty() && emulated.size() == all.size())
    return "emulated (every device's port is 'emulated' in the config)";
  if (emulated.empty()) return "hardware";
  return fmt::format("hardware ({} emulated in-process)", fmt::join(emulated, ", "));
}

journal::RecordInfo record_info(const config::CellConfig& cell, const std::filesystem::path& config_file,
                                const recipe::Recipe& recipe, const recipe::Program& program,
                                runtime::RunMode mode) {
  journal::RecordInfo info;
  info.recipe_file = recipe.source;
  info.recipe_name = recipe.name;
  info.recipe_version = recipe.version;
  info.config_file = config_file;
  info.cell = cell.name;
  info.mode = mode_label(cell, mode);
  for (const auto& d : devices(cell))
    info.ports.push_back(fmt::format(
        "{}: {}", d.name, mode == runtime::RunMode::hardware ? d.port->port : std::string("emulated")));
  for (const auto& a : cell.axes) info.axes.push_back({a.name, a.encoder});
  for (const auto& ins : program.instructions) {
    auto step = std::visit(StepKind{}, ins.action);
    step.label = ins.label;
    info.steps.push_back(std::move(step));
  }
  info.sample_s = cell.loop.sample_ms / 1000.0;
  return info;
}

std::filesystem::path default_run_dir(const std::filesystem::path& recipe_file) {
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return std::filesystem::path("runs") /
         fmt::format("{}-{:%Y%m%d-%H%M%S}", recipe_file.stem().string(), fmt::localtime(now));
}

}  // namespace cellctl::jobs
