#pragma once
// Whole runs in virtual time: the shipped cell config and a recipe, through the real sessions,
// emulators and SimLinks, with a journal in a fresh directory.

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "config/cell_config.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/cell_run.hpp"

namespace cellctl::testing {

inline std::filesystem::path source_dir() {
  return CELLCTL_SOURCE_DIR;
}

// A recipe for the demo cell (config/cell.yaml) named `name`, with the demo's limits — x and z within
// their travel and speed, the spindle 200–600 Hz, 30 s per move, 10 s per spindle step — and `steps`
// (the YAML list's items, one "  - …" line each).
inline std::string demo_recipe(std::string_view name, std::string_view steps) {
  return std::string("recipe: {name: ") + std::string(name) + R"(, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
    z: {min_mm: 0, max_mm: 120, max_speed_mm_s: 12, tolerance_mm: 0.1}
  spindle: {min_hz: 200, max_hz: 600}
  timeouts: {move_s: 30, spindle_s: 10}
steps:
)" + std::string(steps);
}

class RunFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() / (std::string("cellctl-run-") + info->test_suite_name() +
                                                     "-" + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    // The encoder's EEPROM file lives per test, so runs do not see each other's presets.
    cell_ = config::load_cell_config(source_dir() / "config/cell.yaml");
  }
  void TearDown() override {
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }

  void load_recipe(const std::filesystem::path& path) { recipe_ = recipe::load_recipe(path, cell_); }
  void load_recipe_text(const std::string& text) {
    recipe_ = recipe::parse_recipe(config::YamlNode::load_string(text, "test-recipe.yaml"), cell_);
  }

  // The emulators' set-up, read from the cell file on first use: change cell_'s sessions before.
  emulation::EmulatorSetup& emulators() {
    if (!emulators_) {
      emulators_ = emulation::load_emulator_setup(cell_);
      if (emulators_->encoder) emulators_->encoder->state_file = dir_ / "encoder.eeprom";
    }
    return *emulators_;
  }

  runtime::CellRun& make_run() {
    runtime::RunOptions o;
    o.emulators = emulators();
    o.mode = runtime::RunMode::virtual_time;
    o.journal_dir = dir_ / "journal";
    o.supervisor = supervisor_settings_;
    o.faults = faults_;
    o.state_dir = dir_ / "state";  // the home record: each test its own
    o.device_kinds = device_kinds_;
    run_ = std::make_unique<runtime::CellRun>(cell_, recipe_, o);
    return *run_;
  }

  // `interrupt_` is the run's Ctrl-C flag: a test's cycle hook may raise it.
  runtime::RunResult go() { return run_->run(interrupt_); }

  std::vector<nlohmann::json> journal() const {
    std::vector<nlohmann::json> out;
    std::ifstream in(dir_ / "journal" / "journal.jsonl");
    for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
    return out;
  }
  std::vector<nlohmann::json> events(const std::string& kind) const {
    std::vector<nlohmann::json> out;
    for (auto& j : journal())
      if (j["event"] == kind) out.push_back(j);
    return out;
  }
  // Notes of the run that contain `text`.
  std::size_t notes_with(const std::string& text) const {
    std::size_t n = 0;
    for (const auto& e : events("note"))
      if (e["text"].get<std::string>().find(text) != std::string::npos) ++n;
    return n;
  }

  std::filesystem::path dir_;
  config::CellConfig cell_;
  std::optional<emulation::EmulatorSetup> emulators_;
  recipe::Recipe recipe_;
  std::unique_ptr<runtime::CellRun> run_;
  std::atomic<bool> interrupt_{false};
  supervisor::SupervisorSettings supervisor_settings_;  // e.g. move.max_corrections, before make_run()
  std::vector<runtime::FaultSpec> faults_;              // to rehearse, before make_run()
  // The kinds of device of the cell (a test may add one), before make_run().
  std::span<const device_seam::DeviceKind> device_kinds_ = device_seam::cell_device_kinds();
};

}  // namespace cellctl::testing
