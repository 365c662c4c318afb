#pragma once
// What a run's record header is made from (the caller's RecordInfo) and what this process adds to it —
// the files' SHA-256, this cellctl, this host, the start time (UTC). The header itself and its line are
// the schema's (schema/record_header.hpp).

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
