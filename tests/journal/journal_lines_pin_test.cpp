// The run record's lines, byte for byte: one line of every kind the journal writes (the header, each
// event kind with and without its optional fields, a long note, the summary with what a run adds to
// it), as `cellctl report`, `cellctl compare` and every script that reads journal.jsonl know them.
// Pinned from the output before the typed event stream and the schema module (issue 24): a change here
// is a change for the user.

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "journal/event_sink.hpp"
#include "journal/journal.hpp"
#include "journal/record_header.hpp"

namespace cellctl::journal {
namespace {

std::filesystem::path fresh_pin_dir(const std::string& name) {
  auto d = std::filesystem::temp_directory_path() /
           ("cellctl-journal-pin-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::vector<std::string> out;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The header's values that differ from run to run (host, time, version, the test's folder) replaced by
// their names.
std::string masked(std::string line, const std::filesystem::path& dir) {
  for (auto at = line.find(dir.string()); at != std::string::npos; at = line.find(dir.string()))
    line.replace(at, dir.string().size(), "<dir>");
  for (const char* key : {"cellctl", "host", "started_utc"}) {
    const auto k = fmt::format("\"{}\":\"", key);
    const auto at = line.find(k);
    if (at == std::string::npos) continue;
    const auto from = at + k.size();
    line.replace(from, line.find('"', from) - from, fmt::format("<{}>", key));
  }
  return line;
}

// The record header of a run of tests' own files (their hashes pinned with them).
RecordInfo info_in(const std::filesystem::path& dir) {
  std::ofstream(dir / "recipe.yaml") << "recipe: pinned\n";
  std::ofstream(dir / "cell.yaml") << "cell: pinned\n";
  RecordInfo info;
  info.recipe_file = dir / "recipe.yaml";
  info.recipe_name = "pinned";
  info.recipe_version = "1.0";
  info.config_file = dir / "cell.yaml";
  info.cell = "pin-cell";
  info.mode = "virtual time";
  info.ports = {"scu: emulated", "spindle: emulated"};
  info.axes = {{"x", true}, {"z", false}};
  info.steps = {{"go (line 3)", "move", std::nullopt}, {"wait (line 4)", "dwell", 1.5}};
  info.sample_s = 0.02;
  return info;
}

TEST(JournalLines, EveryKindOfLineIsPinned) {
  const auto dir = fresh_pin_dir("every-kind");
  const auto info = info_in(dir);
  std::string long_note = "SCU: ";
  for (int i = 0; long_note.size() < 1100; ++i) long_note += "part " + std::to_string(i) + " — ";
  {
    Journal j(dir, WhenFull::wait, record_header(info));
    j.post(0.0, Command{"start", Text::format("cellctl run")});
    j.post(0.0, RunStarted{"pinned", "pin-cell", "virtual-time", 2});
    j.post(0.0, StateChanged{"Idle", "Starting", Text::format("start by cellctl run")});
    j.post(0.1234567, StateChanged{"Starting", "Execute", {}});
    j.post(0.2, StepStarted{0, "go (line 3)"});
    Sample s;
    s.axes = 2;
    s.planned_mm = {12.3f, -0.00004f};
    s.scu_mm = {12.30006f, 1.5f};
    s.encoder_mm = 12.29f;
    s.encoder_mm_s = 3.33333f;
    s.spindle_set_hz = 400.0f;
    s.spindle_actual_hz = 399.98f;
    j.post(0.22, s);
    j.post(1.0000004, StepEnded{0, "go (line 3)", true, {}});
    j.post(1.1, StepStarted{1, "wait (line 4)"});
    j.post(1.2, Command{"hold", Text::format("plant cellctl/pin/cmd/hold")});
    j.post(1.2, StateChanged{"Execute", "Holding", Text::format("hold by plant")});
    j.post(1.3, Fault{"operator_stop", 2, Text::format("Ctrl-C")});
    j.post(1.4, FaultCleared{"operator_stop"});
    post_note(j, 1.5, "reset refused: the cause of {} is still present", "overspeed");
    post_note(j, 1.6, long_note);
    j.post(2.0, InjectedFault{"scu", "silent", "scu:silent@2+1", "the line carries nothing either way", false,
                              false});
    j.post(2.1, Fault{"link_silent", 0, Text::format("scu silent for 301 ms (limit 300 ms)")});
    j.post(2.2, StepEnded{1, "wait (line 4)", false, Text::format("stopped by the fault")});
    j.post(3.0, InjectedFault{"scu", "silent", "scu:silent@2+1", "the line carries nothing either way", true,
                              false});
    j.post(3.1, InjectedFault{"spindle", "error", "spindle:error@3", "the converter latches fault 31", true,
                              true});
    j.post(3.2, RunEnded{"aborted"});
    // What a run adds to its summary (runtime::CellRun), as a run that a lost SCU link ended has it.
    schema::RunFigures run;
    run.links = {{"scu", 47, 11.0, 100.0, 7, 6, 0}};
    run.cycles = 3217;
    run.jitter_p99_us = 12.5;
    run.wall_s = 0.25;
    run.mode = "virtual-time";
    run.corrections = 1;
    run.teach_in = schema::TeachInFigures{true, 4096, true};
    run.devices = {{"scu", "observed", "every actuator reported at rest"},
                   {"spindle", "unknown", "no answer to CMD System Stopp"}};
    run.ended_by = schema::EndedBy{
        2.1, "link_silent", schema::EndedBy::Kind::link, "scu", "SCU silent for 1001 ms", 1.928, {}};
    j.close(run);
  }
  const auto lines = lines_of(dir / "journal.jsonl");
  const std::vector<std::string> expected = {
      R"J({"axes":[{"measured":true,"name":"x"},{"measured":false,"name":"z"}],"cell":"pin-cell","cellctl":"<cellctl>","config_file":"<dir>/cell.yaml","config_sha256":"7fb65ff0d2c0788995f4a9162d22638e17a155395277ad158395788d9e8d66d2","event":"record","host":"<host>","mode":"virtual time","ports":["scu: emulated","spindle: emulated"],"position_unit":"mm","recipe":"pinned","recipe_file":"<dir>/recipe.yaml","recipe_sha256":"459e0e133d794cba768e1eb55756c34c2e3fb364f1f6f0d28ad742d168a0c0c6","recipe_version":"1.0","sample_s":0.02,"spindle_unit":"Hz","started_utc":"<started_utc>","steps":[{"kind":"move","label":"go (line 3)","step":1},{"kind":"dwell","label":"wait (line 4)","planned_s":1.5,"step":2}],"t":0.0})J",
      R"J({"command":"start","event":"command","source":"cellctl run","t":0.0})J",
      R"J({"cell":"pin-cell","event":"run_started","mode":"virtual-time","recipe":"pinned","steps":2,"t":0.0})J",
      R"J({"event":"state","from":"Idle","reason":"start by cellctl run","t":0.0,"to":"Starting"})J",
      R"J({"event":"state","from":"Starting","t":0.123457,"to":"Execute"})J",
      R"J({"event":"step_started","label":"go (line 3)","step":1,"t":0.2})J",
      R"J({"encoder_mm":12.29,"encoder_mm_s":3.3333,"event":"sample","planned_mm":[12.3,-0.0],"scu_mm":[12.3001,1.5],"spindle_hz":399.98,"spindle_set_hz":400.0,"t":0.22})J",
      R"J({"event":"step_done","label":"go (line 3)","step":1,"t":1.0})J",
      R"J({"event":"step_started","label":"wait (line 4)","step":2,"t":1.1})J",
      R"J({"command":"hold","event":"command","source":"plant cellctl/pin/cmd/hold","t":1.2})J",
      R"J({"event":"state","from":"Execute","reason":"hold by plant","t":1.2,"to":"Holding"})J",
      R"J({"category":2,"detail":"Ctrl-C","event":"fault","rule":"operator_stop","t":1.3})J",
      R"J({"event":"fault_cleared","rule":"operator_stop","t":1.4})J",
      R"J({"event":"note","t":1.5,"text":"reset refused: the cause of overspeed is still present"})J",
      R"J({"event":"note","t":1.6,"text":")J" + long_note + R"J("})J",
      R"J({"device":"scu","event":"fault_injected","kind":"silent","spec":"scu:silent@2+1","t":2.0,"what":"the line carries nothing either way"})J",
      R"J({"category":0,"detail":"scu silent for 301 ms (limit 300 ms)","event":"fault","rule":"link_silent","t":2.1})J",
      R"J({"detail":"stopped by the fault","event":"step_failed","label":"wait (line 4)","step":2,"t":2.2})J",
      R"J({"device":"scu","event":"fault_injection_ended","kind":"silent","spec":"scu:silent@2+1","t":3.0,"what":"the line carries nothing either way"})J",
      R"J({"device":"spindle","event":"fault_injection_ended","kind":"error","spec":"spindle:error@3","still_active":true,"t":3.1,"what":"the converter latches fault 31"})J",
      R"J({"event":"run_ended","outcome":"aborted","t":3.2})J",
      R"J({"corrections":1,"cycles":3217,"devices":{"scu":{"evidence":"every actuator reported at rest","safe":"observed"},"spindle":{"evidence":"no answer to CMD System Stopp","safe":"unknown"}},"duration_s":3.2,"ended_by":{"device":"scu","kind":"link","rule":"link_silent","since_s":1.928,"symptom":"SCU silent for 1001 ms","t":2.1},"event":"summary","faults":["1.300s operator_stop (category 2): Ctrl-C","2.000s injected: scu, silent, scu:silent@2+1, the line carries nothing either way","2.100s link_silent (category 0): scu silent for 301 ms (limit 300 ms)","3.000s injected: scu, silent, scu:silent@2+1, the line carries nothing either way","3.100s injected: spindle, error, spindle:error@3, still_active=true, the converter latches fault 31"],"jitter_p99_us":12.5,"journal_dropped":0,"links":{"scu":{"bad_frames":0,"max_round_trip_ms":11.0,"max_silence_ms":100.0,"replies":47,"retries":6,"timeouts":7}},"missed_deadlines":0,"mode":"virtual-time","outcome":"aborted","overrun_cycles":0,"steps":[{"count":1,"failed":0,"label":"go (line 3)","seconds":0.8},{"count":1,"failed":1,"label":"wait (line 4)","seconds":1.1}],"teach_in":{"encoder_restored":true,"taught":true,"total_resolution":4096},"wall_s":0.25})J",
  };
  ASSERT_EQ(lines.size(), expected.size());
  for (std::size_t i = 0; i < lines.size(); ++i)
    EXPECT_EQ(masked(lines[i], dir), expected[i]) << "line " << i + 1;
  std::filesystem::remove_all(dir);
}

// A run that could not start (a port that did not open) says so in its summary, after no event.
TEST(JournalLines, ARunThatDidNotStart) {
  const auto dir = fresh_pin_dir("not-started");
  {
    Journal j(dir, WhenFull::wait);
    j.close_not_started("cannot open /dev/ttyUSB0: No such file or directory");
  }
  const auto lines = lines_of(dir / "journal.jsonl");
  const std::vector<std::string> expected = {
      R"J({"duration_s":0.0,"event":"summary","faults":[],"journal_dropped":0,"outcome":"not started","reason":"cannot open /dev/ttyUSB0: No such file or directory","steps":[]})J",
  };
  EXPECT_EQ(lines, expected);
  std::filesystem::remove_all(dir);
}

// A run a fault of the monitor ended: its words in the summary's ended_by.
TEST(JournalLines, ARunTheMonitorEnded) {
  const auto dir = fresh_pin_dir("monitor-ended");
  {
    Journal j(dir, WhenFull::wait);
    j.post(0.0, RunStarted{"pinned", "pin-cell", "emulated", 1});
    j.post(0.5, StepStarted{0, "go (line 3)"});
    j.post(0.7, Fault{"emergency_stop", 0, Text::format("Ctrl-C twice")});
    j.post(0.9, RunEnded{"aborted"});
    schema::RunFigures run;
    run.ended_by = schema::EndedBy{0.7, "emergency_stop", schema::EndedBy::Kind::operator_stop, {}, {},
                                   0.0, "Ctrl-C twice"};
    j.close(run);
  }
  const auto lines = lines_of(dir / "journal.jsonl");
  const std::vector<std::string> expected = {
      R"J({"cell":"pin-cell","event":"run_started","mode":"emulated","recipe":"pinned","steps":1,"t":0.0})J",
      R"J({"event":"step_started","label":"go (line 3)","step":1,"t":0.5})J",
      R"J({"category":0,"detail":"Ctrl-C twice","event":"fault","rule":"emergency_stop","t":0.7})J",
      R"J({"event":"run_ended","outcome":"aborted","t":0.9})J",
      R"J({"corrections":0,"cycles":0,"devices":{},"duration_s":0.9,"ended_by":{"detail":"Ctrl-C twice","kind":"operator","rule":"emergency_stop","t":0.7},"event":"summary","faults":["0.700s emergency_stop (category 0): Ctrl-C twice"],"jitter_p99_us":0.0,"journal_dropped":0,"links":null,"missed_deadlines":0,"mode":"","outcome":"aborted","overrun_cycles":0,"steps":[{"count":1,"failed":0,"interrupted":1,"label":"go (line 3)","seconds":0.4}],"wall_s":0.0})J",
  };
  EXPECT_EQ(lines, expected);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cellctl::journal
