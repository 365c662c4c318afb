#include "cli/teach_in_job.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <vector>

namespace cellctl::cli {
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

nlohmann::json teach_in_record_header(const std::filesystem::path& config_file, const std::string& axis,
                                      double distance_mm, runtime::RunMode mode) {
  return {{"record", "teach-in"},
          {"config", config_file},
          {"axis", axis},
          {"distance_mm", distance_mm},
          {"mode", to_string(mode)}};
}

config::ConfigChange write_teach_in_result(const std::filesystem::path& config_file,
                                           const config::CellConfig& cell, const runtime::TeachInOutcome& o) {
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
  return config::change_config_file(config_file, "encoder", changes);
}

}  // namespace cellctl::cli
