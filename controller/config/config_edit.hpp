#pragma once
// Changing the cell config file from a program (commissioning: a preset, a direction change, a
// Teach-In result) the way a technician would by hand: only the named keys of one top-level section
// change, every other line and comment stays as it was. The new file is checked by the same loader
// as every run before it replaces the old one (temp file + rename in the same folder, so a crash
// leaves the old or the new file, never half of one), and the old one is kept as a backup.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cellctl::config {

struct KeyChange {
  std::string key;
  std::optional<std::string> value;  // nullopt: remove the key
};

// `text` with the keys of the block-style top-level mapping `section` set (a key that is not there is
// added as the section's first key) or removed. Throws std::runtime_error when there is no such
// section in block style.
[[nodiscard]] std::string edit_section(std::string_view text, std::string_view section,
                                       const std::vector<KeyChange>& changes);

struct ConfigChange {
  std::filesystem::path backup;      // the file as it was
  std::vector<std::string> changed;  // "encoder.measuring_units: 4096 → 16404200", one per key
};

// Edits `section` of the config file at `path`: the new text must load (load_cell_config) or nothing
// is written; then the old file is copied to `path` + ".bak" and the new one renamed over `path`.
// Throws ConfigError (the new text does not load) or std::runtime_error (I/O), the file untouched.
ConfigChange change_config_file(const std::filesystem::path& path, std::string_view section,
                                const std::vector<KeyChange>& changes);

// The same change, written to `destination` instead (a dry run's copy, e.g. state/config.dry-run.yaml:
// folders made, replaced whole): `source` is only read, and no backup is made (`backup` stays empty).
ConfigChange change_config_copy(const std::filesystem::path& source, const std::filesystem::path& destination,
                                std::string_view section, const std::vector<KeyChange>& changes);

// `text` as the whole file at `path`: written to a temporary file in the same folder, flushed to disk
// and renamed over `path`, so a crash leaves the old or the new file. Throws std::runtime_error.
void replace_file(const std::filesystem::path& path, std::string_view text);

}  // namespace cellctl::config
