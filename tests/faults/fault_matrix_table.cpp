// Prints the fault matrix (fault_matrix.hpp) as a table: per case the injected fault, when the fault
// was detected and when the plant was at rest (ms after the injection, with their bounds), the safe
// state the journal's summary gives per device, and the verdict; below it each failed case's reasons.
// Exit status 0 when every case passes, 1 otherwise.
//
//   fault_matrix_table [--keep DIR] [--cellctl PATH] [FILTER]
//     FILTER     runs only the cases whose name (device/fault/activity) contains it, e.g. spindle_on
//     --keep     leaves each case's run record under DIR (for cellctl report / the plots)
//     --cellctl  runs each case a second time through that cellctl binary and judges its exit status

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>

#include "faults/fault_matrix.hpp"

using namespace cellctl::faults;

namespace {

std::string time_cell(const std::optional<double>& ms, double bound) {
  return ms ? fmt::format("{:>5.0f} ≤{:<5.0f}", *ms, bound) : fmt::format("{:>5} ≤{:<5.0f}", "-", bound);
}

std::string safe_cell(const Outcome& o) {
  std::string out;
  for (const auto d : kDevices) {
    const auto& s = o.devices.safe[static_cast<std::size_t>(d)];
    out += fmt::format("{:<9}", s ? to_string(*s) : "-");
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string filter;
  std::filesystem::path keep;
  std::filesystem::path cellctl;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--keep") == 0 && has_value) {
      keep = argv[++i];
    } else if (std::strcmp(argv[i], "--cellctl") == 0 && has_value) {
      cellctl = argv[++i];
    } else if (argv[i][0] == '-') {
      fmt::print(stderr, "usage: {} [--keep DIR] [--cellctl PATH] [FILTER]\n", argv[0]);
      return 2;
    } else {
      filter = argv[i];
    }
  }
  const auto cell = matrix_cell();
  const auto work = keep.empty() ? std::filesystem::temp_directory_path() /
                                       ("cellctl-fault-matrix-table-" + std::to_string(::getpid()))
                                 : keep;
  fmt::print(
      "fault at {:g} s for {:g} s; times in ms after the injection (measured ≤bound); safe: scu spindle "
      "encoder\n\n",
      kInjectAtS, kLastingS);
  fmt::print("{:<32} {:<22} {:<12} {:<12} {:<27} {}\n", "case", "--fault", "detected", "safe after",
             "safe per device", cellctl.empty() ? "verdict" : "exit verdict");
  std::vector<std::pair<std::string, std::vector<std::string>>> failed;
  int cases = 0;
  const auto wall = std::chrono::steady_clock::now();
  for (const auto& c : all_cases()) {
    const auto name = name_of(c);
    if (!filter.empty() && name.find(filter) == std::string::npos) continue;
    ++cases;
    const auto e = expectation(c, cell);
    auto o = run_case(c, cell, work, !keep.empty());
    if (!cellctl.empty()) {
      o.exit_status = cellctl_exit_status(c, cell, cellctl, work);
      if (!o.exit_status) o.setup_error += " (cellctl did not exit normally)";
    }
    auto problems = verdict(c, e, o);
    fmt::print(
        "{:<32} {:<22} {:<12} {:<12} {:<27} {}\n", name, fault_spec_text(c, cell),
        e.fault_detected ? time_cell(o.detected_ms, e.detect_ms) : (o.detected_ms ? "FAULT" : "none"),
        e.fault_detected ? time_cell(o.safe_ms, e.safe_ms) : (o.safe_ms ? "at the end" : "NOT AT REST"),
        safe_cell(o),
        (o.exit_status ? fmt::format("{:<4} ", *o.exit_status) : std::string()) +
            (problems.empty() ? "pass" : "FAIL"));
    std::fflush(stdout);
    if (!problems.empty()) failed.emplace_back(name, std::move(problems));
  }
  if (keep.empty()) std::filesystem::remove_all(work);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  fmt::print("\n{} cases, {} passed, {} failed ({:.1f} s wall)\n", cases,
             cases - static_cast<int>(failed.size()), failed.size(), wall_s);
  // The bounds, per device and fault class: detection's reasoning, and the plant's rest per activity.
  fmt::print(
      "\nbounds from config/cell.yaml, ms after the injection (plant at rest: idle | moving | "
      "spindle_on):\n");
  for (const auto d : kDevices) {
    for (const auto f : kFaultClasses) {
      std::string rest;
      std::string why;
      for (const auto a : kActivities) {
        const auto e = expectation({d, f, a}, cell);
        if (!e.fault_detected) {
          why = e.why;
          break;
        }
        why = e.detect_why;
        rest += fmt::format("{}{:.0f}", rest.empty() ? "" : " | ", e.safe_ms);
      }
      const auto e = expectation({d, f, Activity::idle}, cell);
      if (e.fault_detected)
        fmt::print("  {:<20} detected ≤ {:.0f} ({}); at rest ≤ {}\n",
                   fmt::format("{}/{}", cellctl::cell::to_string(d), to_string(f)), e.detect_ms, why, rest);
      else
        fmt::print("  {:<20} no fault ({})\n",
                   fmt::format("{}/{}", cellctl::cell::to_string(d), to_string(f)), why);
    }
  }
  fmt::print(
      "  at rest: idle: at rest already; moving: detected + stopping 500, or, the SCU's line down, its\n"
      "  watchdog 500 + stopping 500; spindle on: detected + run-down 1250, or, the converter's line down,\n"
      "  the line back (2000) + run-down 1250\n");
  for (const auto& [name, problems] : failed) {
    fmt::print("\n{}:\n", name);
    for (const auto& p : problems) fmt::print("  - {}\n", p);
  }
  return failed.empty() ? 0 : 1;
}
