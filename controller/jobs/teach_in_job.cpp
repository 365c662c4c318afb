#include "jobs/teach_in_job.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "runtime/dry_run_state.hpp"

namespace cellctl::jobs {
namespace {

std::string number(double v) {
  return fmt::format("{:.6g}", v);
}

}  // namespace

std::variant<routines::TeachInRequest, std::string> teach_in_request(const config::CellConfig& cell,
                                                                     const TeachInAsk& ask) {
  routines::TeachInRequest request;
  request.axis = -1;
  for (std::size_t i = 0; i < cell.axes.size(); ++i)
    if (cell.axes[i].name == ask.axis) request.axis = static_cast<int>(i);
  if (request.axis < 0) return fmt::format("the cell has no axis '{}'", ask.axis);
  const auto& axis = cell.axes[static_cast<std::size_t>(request.axis)];
  if (!axis.encoder)
    return fmt::format("the encoder does not measure axis {} (encoder: true is on another axis or none)",
                       ask.axis);
  request.distance_mm = ask.distance_mm;
  request.from_mm = ask.from_mm;
  request.manual = ask.manual;
  request.speed_mm_s = ask.speed_mm_s.value_or(std::min(5.0, axis.max_speed_mm_s));
  request.tolerance_mm = ask.tolerance_mm;
  return request;
}

recipe::Recipe teach_in_recipe(const config::CellConfig& cell, const routines::TeachInRequest& request,
                               const std::filesystem::path& run_dir) {
  const auto& axis = cell.axes.at(static_cast<std::size_t>(request.axis));
  recipe::Recipe r;
  r.name = fmt::format("teach-in {}", axis.name);  // as the page and the plant name the job
  r.version = std::string(1, '1');                 // (not = "1": g++ 12 -O2 warns a false -Wrestrict on that)
  r.cell = cell.name;
  r.limits.axes.resize(cell.axes.size());  // no recipe move: the routine keeps to the axis's own limits
  r.steps.push_back({fmt::format("teach-in {}", axis.name), 1, request});
  std::filesystem::create_directories(run_dir);
  r.source = (run_dir / "teach-in.yaml").string();
  std::ofstream out(r.source);
  out << fmt::format(
      "# Written by cellctl: the Teach-In this run record is of (a description, not a recipe).\n"
      "teach_in: {{axis: {}, distance_mm: {}, from_mm: {}, manual: {}, speed_mm_s: {}, tolerance_mm: {}}}\n",
      axis.name, number(request.distance_mm), request.from_mm ? number(*request.from_mm) : "null",
      request.manual, number(request.speed_mm_s), number(request.tolerance_mm));
  if (!out) throw std::runtime_error(fmt::format("cannot write {}", r.source));
  return r;
}

namespace {

// The taught resolution into the encoder section of `config_file`'s text, as the manual asks (4.4.2.1
// "End": into Maximum Desired Measuring Units), with the unit per mm it counts in; written over the
// config (the old file kept as FILE.bak) or into `destination` when that is another file.
config::ConfigChange write_result(const std::filesystem::path& config_file,
                                  const std::filesystem::path& destination, const config::CellConfig& cell,
                                  const runtime::TeachInOutcome& o) {
  std::vector<config::KeyChange> changes = {
      {"scaling", "true"},
      {"units_select", "per_total_range"},
      {"measuring_units", std::to_string(o.result.total_resolution)},
      {"counts_per_mm", number(o.units_per_mm)},
      {"mm_per_revolution", std::nullopt},
      {"preset_offset", "0"},
  };
  if (cell.encoder->session.zero_offset_mm != 0.0)
    changes.push_back({"zero_offset_mm", number(o.taught.zero_offset_mm)});
  if (destination == config_file) return config::change_config_file(config_file, "encoder", changes);
  return config::change_config_copy(config_file, destination, "encoder", changes);
}

}  // namespace

std::filesystem::path teach_in_destination(const std::filesystem::path& config_file,
                                           const config::CellConfig& cell, runtime::RunMode mode,
                                           const std::filesystem::path& state_dir) {
  // A rehearsal on emulators never rewrites the cell's config: its result goes into a copy.
  if (mode == runtime::RunMode::hardware) return config_file;
  return runtime::dry_run_config_file(state_dir.empty() ? cell.state_dir : state_dir);
}

TeachInRecord record_teach_in(const std::filesystem::path& config_file, const config::CellConfig& cell,
                              const runtime::RunResult& r, runtime::RunMode mode,
                              const std::filesystem::path& state_dir, bool manual) {
  TeachInRecord out;
  if (!r.teach_in) return out;
  const auto& o = *r.teach_in;
  if (!o.done) {
    out.words =
        fmt::format("Teach-In failed: {}; {}; {} is not changed", o.failure,
                    o.restored ? "the encoder's configured parameters are restored"
                               : "the encoder's configured parameters could NOT be confirmed restored: "
                                 "check with `cellctl encoder diag` before any run",
                    config_file.string());
    return out;
  }
  out.words = fmt::format(
      "Teach-In done: total resolution {} (units per maximum total measuring range), {:g} units per mm; "
      "verified: moving back, the encoder measured {:.4f} mm, the {} {:.4f} mm",
      o.result.total_resolution, o.units_per_mm, o.result.encoder_distance_mm,
      manual ? "distance given" : "SCU", o.result.scu_back_mm);
  const bool dry_run = mode != runtime::RunMode::hardware;
  out.file = teach_in_destination(config_file, cell, mode, state_dir);
  try {
    const auto change = write_result(config_file, out.file, cell, o);
    out.written = true;
    out.words += fmt::format("; {} written ({})", out.file.string(), fmt::join(change.changed, "; "));
    if (dry_run)
      out.words += fmt::format("; a dry run: {} is not changed (compare, then copy what you want)",
                               config_file.string());
    else
      out.words += fmt::format("; the previous config is {}", change.backup.string());
  } catch (const std::exception& e) {
    out.write_failed = true;
    out.words += fmt::format("; but {} was not written: {}", out.file.string(), e.what());
  }
  return out;
}

}  // namespace cellctl::jobs
