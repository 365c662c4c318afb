#include "runtime/home_record_file.hpp"

#include <fstream>
#include <iterator>
#include <stdexcept>

#include "config/config_edit.hpp"
#include "schema/state_files.hpp"

namespace cellctl::runtime {
namespace {

config::HomingStrategy strategy_from(const std::string& s) {
  for (auto k : {config::HomingStrategy::absolute_encoder, config::HomingStrategy::end_position,
                 config::HomingStrategy::scu_initialised})
    if (s == config::to_string(k)) return k;
  return config::HomingStrategy::none;
}

}  // namespace

std::filesystem::path home_record_path(const std::filesystem::path& state_dir,
                                       std::string_view dry_run_mode) {
  return state_dir /
         (dry_run_mode.empty() ? std::string("home.json") : "home." + std::string(dry_run_mode) + ".json");
}

routines::HomeRecord load_home_record(const std::filesystem::path& file, const config::CellCore& cell,
                                      const std::string& config_sha256, std::string* problem) {
  routines::HomeRecord r;
  r.config_sha256 = config_sha256;
  std::ifstream in(file);
  if (!in) return r;
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  auto read = schema::read_home_record_json(text);
  if (const auto* why = std::get_if<std::string>(&read)) {
    if (problem) *problem = file.string() + " is no home record (" + *why + "); it counts as empty";
    return r;
  }
  const auto& kept = std::get<schema::HomeRecordFile>(read);
  r.config_changed = kept.config_sha256 != config_sha256;
  for (const auto& a : kept.axes)
    for (std::size_t i = 0; i < cell.axes.size(); ++i) {
      if (cell.axes[i].name != a.name) continue;
      auto& h = r.axes[i];
      h.homed = true;
      h.strategy = strategy_from(a.strategy);
      h.measured = a.encoder_mm.has_value();
      h.encoder_mm = a.encoder_mm.value_or(h.encoder_mm);
      h.scu_mm = a.scu_mm;
      h.unix_time = a.unix_time;
    }
  return r;
}

void save_home_record(const std::filesystem::path& file, const routines::HomeRecord& record,
                      const config::CellCore& cell) {
  schema::HomeRecordFile kept{record.config_sha256, cell.source.string(), {}};
  for (std::size_t i = 0; i < cell.axes.size(); ++i) {
    const auto& h = record.axes[i];
    if (!h.homed) continue;
    kept.axes.push_back({cell.axes[i].name, std::string(config::to_string(h.strategy)),
                         h.measured ? std::optional<double>(h.encoder_mm) : std::nullopt, h.scu_mm,
                         h.unix_time});
  }
  try {
    std::error_code ec;
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
    if (ec) throw std::runtime_error("cannot create its folder: " + ec.message());
    config::replace_file(file, schema::home_record_json(kept));
  } catch (const std::exception& e) {
    throw std::runtime_error("home record " + file.string() + ": " + e.what());
  }
}

}  // namespace cellctl::runtime
