#pragma once
// The first line of every run record: what is needed to reproduce the run and to read its samples —
// the recipe file and its SHA-256, the config file and its SHA-256, which cellctl wrote it, the mode,
// the host, when it started (UTC), the axes' names and units, and the steps as the run numbers them.
// journal/record_header.hpp fills it in for a run; read back, a key the line lacks stays empty.

#include <optional>
#include <string>
#include <vector>

namespace cellctl::schema {

struct RecordHeader {
  std::optional<std::string> recipe_file;
  std::optional<std::string> recipe_sha256;
  std::optional<std::string> recipe;
  std::optional<std::string> recipe_version;
  std::optional<std::string> config_file;
  std::optional<std::string> config_sha256;
  std::optional<std::string> cell;
  std::optional<std::string> cellctl;
  std::optional<std::string> mode;  // hardware, emulated, virtual time, in words
  std::vector<std::string> ports;   // one line per device: where it was reached
  std::optional<std::string> host;
  std::optional<std::string> started_utc;
  double sample_s = 0.02;
  struct Axis {
    std::optional<std::string> name;
    bool measured = false;  // the encoder measures this axis: samples' encoder_mm belong to it
  };
  std::vector<Axis> axes;
  struct Step {  // numbered from 1 in the order given
    std::string label;
    std::string kind;                 // move, spindle, dwell, wait, require
    std::optional<double> planned_s;  // known before the run (a dwell); a move's comes from its profile
  };
  std::vector<Step> steps;
};

// {"t":0,"event":"record",…}.
[[nodiscard]] std::string header_line(const RecordHeader& h);

}  // namespace cellctl::schema
