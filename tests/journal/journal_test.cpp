#include "journal/journal.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "journal/event_sink.hpp"
#include "journal/run_record.hpp"

namespace cellctl::journal {
namespace {

std::filesystem::path fresh_dir(const std::string& name) {
  auto d =
      std::filesystem::temp_directory_path() / ("cellctl-journal-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d;
}

std::vector<nlohmann::json> read_lines(const std::filesystem::path& file) {
  std::vector<nlohmann::json> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
  return out;
}

TEST(Journal, WritesEveryEventAsOneJsonLineThenTheSummary) {
  const auto dir = fresh_dir("lines");
  {
    Journal j(dir, WhenFull::wait);
    j.post(0.0, RunStarted{"demo", "cell", "virtual-time", 2});
    j.post(0.1, StateChanged{"Idle", "Starting", Text::format("operator start")});
    j.post(0.2, StepStarted{0, "go (line 3)"});
    Sample s;
    s.axes = 2;
    s.planned_mm = {1.0f, 2.0f};
    s.scu_mm = {0.5f, 1.5f};
    s.encoder_mm = 0.5f;
    s.spindle_actual_hz = 100.0f;
    j.post(0.3, s);
    j.post(1.2, StepEnded{0, "go (line 3)", true, {}});
    j.post(1.3, RunEnded{"complete"});
    schema::RunFigures run;
    run.cycles = 1300;
    j.close(run);
  }
  const auto lines = read_lines(dir / "journal.jsonl");
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0]["event"], "run_started");
  EXPECT_EQ(lines[1]["to"], "Starting");
  EXPECT_EQ(lines[1]["reason"], "operator start");
  EXPECT_EQ(lines[3]["event"], "sample");
  EXPECT_EQ(lines[3]["scu_mm"].size(), 2u);
  EXPECT_EQ(lines[4]["event"], "step_done");
  EXPECT_EQ(lines[6]["event"], "summary");
  EXPECT_EQ(lines[6]["outcome"], "complete");
  EXPECT_EQ(lines[6]["cycles"], 1300);
  EXPECT_NEAR(lines[6]["steps"][0]["seconds"].get<double>(), 1.0, 1e-9);
  std::ifstream svg(dir / "plot.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), {});
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("<polyline"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(Journal, NotesAreNeverCut) {
  const auto dir = fresh_dir("long-notes");
  std::string reason;
  for (int i = 0; reason.size() < 1000; ++i)
    reason += "part " + std::to_string(i) + " — ";    // multi-byte dashes
  const std::string exact(Text{}.chars.size(), 'x');  // exactly one event's worth
  {
    Journal j(dir, WhenFull::wait);
    post_note(j, 0.5, "SCU: {}", reason);
    post_note(j, 0.6, exact);
    post_note(j, 0.7, "short");
    j.close();
  }
  const auto lines = read_lines(dir / "journal.jsonl");
  ASSERT_EQ(lines.size(), 4u);  // three notes, then the summary
  EXPECT_EQ(lines[0]["text"], "SCU: " + reason);
  EXPECT_EQ(lines[0]["t"], 0.5);
  EXPECT_EQ(lines[1]["text"], exact);
  EXPECT_EQ(lines[2]["text"], "short");
  std::filesystem::remove_all(dir);
}

TEST(Journal, PostedEventsReachTheFileWithoutClosing) {
  // What a Ctrl-C or a crash would leave: the writer flushes each batch on its own.
  const auto dir = fresh_dir("flush");
  Journal j(dir, WhenFull::wait);
  j.post(0.0, Fault{"overspeed", 1, Text::format("x at 30 mm/s")});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  std::vector<nlohmann::json> lines;
  while (lines.empty() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    lines = read_lines(dir / "journal.jsonl");
  }
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0]["rule"], "overspeed");
  j.close();
  std::filesystem::remove_all(dir);
}

TEST(Journal, WaitModeLosesNothingUnderAFlood) {
  const auto dir = fresh_dir("flood");
  constexpr int kEvents = 50'000;  // several times the queue
  {
    Journal j(dir, WhenFull::wait);
    for (int i = 0; i < kEvents; ++i) j.post(i * 0.001, Note{Text::format("n{}", i)});
    j.close();
    EXPECT_EQ(j.dropped(), 0u);
  }
  const auto lines = read_lines(dir / "journal.jsonl");
  ASSERT_EQ(lines.size(), static_cast<std::size_t>(kEvents) + 1);
  EXPECT_EQ(lines[kEvents - 1]["text"], "n49999");
  std::filesystem::remove_all(dir);
}

// One reading of the record: what the journal kept while it wrote (its plots, its summary) is what
// `cellctl report` reads back from the file.
TEST(Journal, TheRecordReadBackIsTheOneItKeptWhileWriting) {
  const auto dir = fresh_dir("read-back");
  std::string long_note;
  while (long_note.size() < 3000) long_note += "a long device note — ";
  schema::RecordHeader header;
  header.recipe = "demo";
  header.recipe_version = "";
  header.recipe_file = "recipes/demo.yaml";
  header.axes = {{"x", true}, {"z", false}};
  header.steps = {{"go (line 3)", "move", std::nullopt}, {"wait (line 4)", "dwell", 0.5}};
  {
    Journal j(dir, WhenFull::wait, header);
    j.post(0.0000004, RunStarted{"demo", "cell", "virtual-time", 2});
    j.post(0.1, StepStarted{0, "go (line 3)"});
    for (int i = 0; i < 50; ++i) {
      Sample s;
      s.axes = 2;
      s.planned_mm = {1000.0f / 3.0f + static_cast<float>(i) * 0.123457f, -2.00004f};
      s.scu_mm = {0.33333f * static_cast<float>(i), 59999.99f};
      s.encoder_mm = 12.34567f;
      s.spindle_set_hz = 400.0f;
      s.spindle_actual_hz = 399.99995f;
      j.post(0.1 + i * 0.0200000003, s);
    }
    j.post(1.2, Command{"hold", Text::format("terminal")});
    j.post(1.2, StateChanged{"Execute", "Holding", {}});
    j.post(1.4, StateChanged{"Held", "Unholding", {}});
    post_note(j, 1.5, long_note);
    j.post(1.6, InjectedFault{"scu", "silent", "scu:silent@1.6", "the line carries nothing", true, true});
    j.post(1.7, Fault{"overspeed", 1, Text::format("x at 30 mm/s")});
    j.post(1.8, StepEnded{0, "go (line 3)", false, Text::format("stopped")});
    j.post(1.9, RunEnded{"stopped"});
    j.close();
    const auto& kept = j.summary().record();
    const auto read = RunRecord::load(dir);
    ASSERT_EQ(read.samples().size(), kept.samples().size());
    for (std::size_t i = 0; i < kept.samples().size(); ++i) {
      const auto &a = kept.samples()[i], &b = read.samples()[i];
      EXPECT_EQ(a.t, b.t);
      EXPECT_EQ(a.planned_mm, b.planned_mm);
      EXPECT_EQ(a.scu_mm, b.scu_mm);
      EXPECT_EQ(a.encoder_mm, b.encoder_mm);
      EXPECT_EQ(a.spindle_set_hz, b.spindle_set_hz);
      EXPECT_EQ(a.spindle_hz, b.spindle_hz);
    }
    ASSERT_EQ(read.steps().size(), kept.steps().size());
    for (std::size_t i = 0; i < kept.steps().size(); ++i) {
      const auto &a = kept.steps()[i], &b = read.steps()[i];
      EXPECT_EQ(std::tie(a.step, a.label, a.start, a.end, a.held_s, a.result, a.detail),
                std::tie(b.step, b.label, b.start, b.end, b.held_s, b.result, b.detail));
    }
    ASSERT_EQ(read.marks().size(), kept.marks().size());
    for (std::size_t i = 0; i < kept.marks().size(); ++i) {
      EXPECT_EQ(read.marks()[i].t, kept.marks()[i].t);
      EXPECT_EQ(read.marks()[i].kind, kept.marks()[i].kind);
      EXPECT_EQ(read.marks()[i].text, kept.marks()[i].text);
    }
    EXPECT_EQ(read.marks()[1].text, long_note);
    EXPECT_EQ(read.outcome(), kept.outcome());
    EXPECT_EQ(read.start(), kept.start());
    EXPECT_EQ(read.end(), kept.end());
    EXPECT_EQ(read.recipe_label(), kept.recipe_label());
    EXPECT_EQ(read.recipe_label(), "demo  (recipes/demo.yaml)");
    EXPECT_EQ(read.axis_names(), kept.axis_names());
    EXPECT_EQ(read.measured_axis(), kept.measured_axis());
    EXPECT_EQ(read.planned_s(read.steps()[0]), kept.planned_s(kept.steps()[0]));
    EXPECT_FALSE(read.loop_figures().has_value());  // no run added its loop figures
  }
  std::filesystem::remove_all(dir);
}

TEST(Journal, UnwritableDirectoryIsNamed) {
  EXPECT_THROW(Journal("/proc/cellctl-cannot-write-here", WhenFull::wait), std::runtime_error);
}

}  // namespace
}  // namespace cellctl::journal
