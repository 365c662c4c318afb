#pragma once
// The encoder's Teach-In as a job: the request for an axis, and writing a verified result into the
// cell config — what `cellctl teach-in` does and what `cellctl serve` does when the plant or the page
// asks.

#include <filesystem>
#include <optional>
#include <string>
#include <variant>

#include "config/cell_config.hpp"
#include "config/config_edit.hpp"
#include "recipe/recipe.hpp"
#include "routines/teach_in.hpp"
#include "runtime/cell_run.hpp"

namespace cellctl::jobs {

struct TeachInAsk {
  std::string axis;
  double distance_mm = 0.0;
  std::optional<double> from_mm;
  bool manual = false;
  std::optional<double> speed_mm_s;  // default: 5 mm/s, at most the axis's
  double tolerance_mm = 0.05;
};

// The routine's request, or why not (no such axis, the encoder does not measure it).
[[nodiscard]] std::variant<routines::TeachInRequest, std::string> teach_in_request(
    const config::CellConfig& cell, const TeachInAsk& ask);

// The Teach-In as a program of one step, run by runtime::CellRun as any recipe is (the monitor, the
// safe stop, samples and plot). What it does is written to `run_dir`/teach-in.yaml, the record's
// "recipe" (a description, not a recipe to load: a Teach-In step is never part of a recipe file, since
// only the job that runs it writes what it taught into the config).
[[nodiscard]] recipe::Recipe teach_in_recipe(const config::CellConfig& cell,
                                             const routines::TeachInRequest& request,
                                             const std::filesystem::path& run_dir);

// What a Teach-In job came to once its run has ended, and what it wrote.
struct TeachInRecord {
  std::string words;           // for the terminal and the end state's reason
  bool written = false;        // the taught resolution is in `file`
  bool write_failed = false;   // verified, but `file` could not be written
  std::filesystem::path file;  // the config written: the cell's, or a dry run's copy
};

// Where a Teach-In's verified result is written: the cell's config, or in a dry run (`mode` not
// hardware) <state_dir>/config.dry-run.yaml (`state_dir` empty: the config's).
[[nodiscard]] std::filesystem::path teach_in_destination(const std::filesystem::path& config_file,
                                                         const config::CellConfig& cell,
                                                         runtime::RunMode mode,
                                                         const std::filesystem::path& state_dir);

// A verified result into the config's encoder section (temp file + rename, the old file kept as
// FILE.bak); a dry run (`mode` not hardware) writes <state_dir>/config.dry-run.yaml instead and never
// the cell's config (`state_dir` empty: the config's). A failed Teach-In writes nothing and says why.
[[nodiscard]] TeachInRecord record_teach_in(const std::filesystem::path& config_file,
                                            const config::CellConfig& cell, const runtime::RunResult& r,
                                            runtime::RunMode mode, const std::filesystem::path& state_dir,
                                            bool manual);

}  // namespace cellctl::jobs
