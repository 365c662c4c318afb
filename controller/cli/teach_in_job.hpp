#pragma once
// The encoder's Teach-In as a job: the request for an axis, and writing a verified result into the
// cell config — what `cellctl teach-in` does and what `cellctl serve` does when the plant or the page
// asks.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>

#include "config/cell_config.hpp"
#include "config/config_edit.hpp"
#include "routines/teach_in.hpp"
#include "runtime/teach_in_run.hpp"

namespace cellctl::cli {

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

// The head of a Teach-In's record.
[[nodiscard]] nlohmann::json teach_in_record_header(const std::filesystem::path& config_file,
                                                    const std::string& axis, double distance_mm,
                                                    runtime::RunMode mode);

// The taught resolution into the config's encoder section, as the manual asks (4.4.2.1 "End": into
// Maximum Desired Measuring Units), with the unit per mm it counts in: temp file + rename, the old
// file kept as FILE.bak. Throws what config::change_config_file throws.
config::ConfigChange write_teach_in_result(const std::filesystem::path& config_file,
                                           const config::CellConfig& cell, const runtime::TeachInOutcome& o);

}  // namespace cellctl::cli
