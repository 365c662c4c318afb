#pragma once
// The first line of every run record: what is needed to reproduce the run and to read its samples —
// the recipe file and its SHA-256, the config file and its SHA-256, which cellctl wrote it, the mode,
// the host, when it started (UTC), the axes' names and units, and the steps as the run numbers them.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "schema/record_header.hpp"

namespace cellctl::journal {

struct RecordAxis {
  std::string name;
  bool measured = false;  // the encoder measures this axis: samples' encoder_mm belong to it
};

struct RecordStep {
  std::string label;
  std::string kind;                 // move, spindle, dwell, wait, require
  std::optional<double> planned_s;  // known before the run (a dwell); a move's comes from its profile
};

struct RecordInfo {
  std::filesystem::path recipe_file;
  std::string recipe_name;
  std::string recipe_version;
  std::filesystem::path config_file;
  std::string cell;
  std::string mode;                // hardware, emulated, virtual-time
  std::vector<std::string> ports;  // one line per device: where it was reached
  std::vector<RecordAxis> axes;
  std::vector<RecordStep> steps;
  double sample_s = 0.02;
};

// The header of a run from now on (its line: schema/record_header.hpp): the files' hashes, this
// cellctl, this host, the time. Throws std::runtime_error naming a file it cannot read.
[[nodiscard]] schema::RecordHeader record_header(const RecordInfo& info);

// Lower-case hex SHA-256 of a file's bytes, as `sha256sum` prints it.
[[nodiscard]] std::string file_sha256(const std::filesystem::path& file);

}  // namespace cellctl::journal
