#pragma once
// The home record on disk: <state_dir>/home.json, one JSON object (schema/state_files.hpp: the
// config's SHA-256, per axis name its strategy, encoder and SCU positions at home and the UTC time).
// Written whole to a temporary file in the same folder, flushed, then renamed over the old one
// (config::replace_file): a crash leaves the old record or the new one, never half of either. Outside
// the control cycle only; the routines keep the record as plain data (routines/home_record.hpp).

#include <filesystem>
#include <string>
#include <string_view>

#include "config/cell_core.hpp"
#include "routines/home_record.hpp"

namespace cellctl::runtime {

// <state_dir>/home.json for the cell itself; a dry run on emulators keeps its own record beside it
// (home.virtual-time.json, home.emulated.json) and never touches the cell's: `dry_run_mode` is the
// run's mode name, empty for the cell itself.
[[nodiscard]] std::filesystem::path home_record_path(const std::filesystem::path& state_dir,
                                                     std::string_view dry_run_mode = {});

// A missing file is an empty record (nothing homed). A file that does not parse is an empty record
// too, and `problem` says why (the next homing replaces it). config_changed is set when the record
// was made with another config than `config_sha256`.
[[nodiscard]] routines::HomeRecord load_home_record(const std::filesystem::path& file,
                                                    const config::CellCore& cell,
                                                    const std::string& config_sha256,
                                                    std::string* problem = nullptr);

// Throws std::runtime_error naming the file ("home record <file>: …") and the reason.
void save_home_record(const std::filesystem::path& file, const routines::HomeRecord& record,
                      const config::CellCore& cell);

}  // namespace cellctl::runtime
