// What the plant reads on its broker, byte for byte: every payload the link publishes — online, the
// state, mode and admin tags, the status, and the answers to commands (accepted, refused by the run's
// words, refused at once, ended with the run, a retained one ignored) — for a run's events of every
// kind, as a dashboard or an MES knows them. Pinned from the output before the typed event stream and
// the schema module (issue 24): a change here is a change for the plant.
//
// No run: the events go to the link as the run's journal hands them over, commands reach a job that
// only says it took them, so every byte is the link's own.

#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <string>
#include <vector>

#include "command/arbiter.hpp"
#include "config/cell_core.hpp"
#include "journal/event.hpp"
#include "plant_link/plant_link.hpp"
#include "plant_test_support.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;
using Message = MqttProbe::Message;
using namespace journal;

config::CellCore pin_cell() {
  config::CellCore c;
  c.name = "demo-cell";  // the example broker's ACL has this cell only
  c.axes.resize(2);
  c.axes[0].name = "x";
  c.axes[1].name = "z";
  return c;
}

class PlantPayloadPin : public ::testing::Test {
 protected:
  void SetUp() override {
    broker_.start();
    auto c = test_link_config(broker_, cell_.name);
    c.recipes = std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/cli";
    c.status_period = 100ms;
    arbiter_.attach({[this] { return state_.load(); },
                     [this](command::Command, const command::CommandSource&) {
                       ++requests_;
                       return command::Taken{command::Taken::How::by_run, {}};
                     }});
    (void)arbiter_.start({{}, std::chrono::steady_clock::now(), {}}, [] {
      return command::Taken{command::Taken::How::done, "started"};
    });
    plant_link::RunAccess access;
    access.arbiter = &arbiter_;
    access.status = [] { return std::optional<plant_link::LiveRun>(); };
    access.mode = "virtual-time";
    plant_probe_.emplace(broker_.port(), "dashboard", MqttBroker::kDashboardPassword,
                         std::string(MqttBroker::kPrefix) + "/#");
    mes_probe_.emplace(broker_.port(), "mes", MqttBroker::kMesPassword,
                       std::string(MqttBroker::kPrefix) + "/#");
    ASSERT_EQ(plant_probe_->wait_connack(), 0);
    ASSERT_EQ(mes_probe_->wait_connack(), 0);
    link_ = std::make_unique<plant_link::PlantLink>(c, cell_, access);
    ASSERT_TRUE(wait_until([&] { return link_->counters().connected; }, 10s));
    ASSERT_TRUE(plant_probe_->wait_for([](const Message& m) { return MqttProbe::on(m, "/admin"); }));
  }

  // An event as the run's journal hands it to the link (its notes whole).
  void feed(double t, const Payload& p) {
    if (const auto* note = std::get_if<Note>(&p))
      link_->events().on_note(t, note->text.view());
    else
      link_->events().on_event({t, p});
  }

  // A command from the MES, once the link has handed it to the job.
  void command(const std::string& word, const std::string& payload, command::State state) {
    state_.store(state);
    const int before = requests_.load();
    mes_probe_->publish(std::string(MqttBroker::kPrefix) + "/demo-cell/cmd/" + word, payload);
    ASSERT_TRUE(wait_until([&] { return requests_.load() > before; }, 10s))
        << word << " never reached the job";
  }

  // Every payload on `tag` so far, in order.
  std::vector<std::string> on(const std::string& tag) {
    std::vector<std::string> out;
    for (const auto& m : plant_probe_->messages())
      if (MqttProbe::on(m, "/" + tag)) out.push_back(m.payload);
    return out;
  }

  std::filesystem::path dir_ =
      std::filesystem::temp_directory_path() / ("cellctl-payload-pin-" + std::to_string(::getpid()));
  MqttBroker broker_{dir_ / "broker"};
  config::CellCore cell_ = pin_cell();
  std::atomic<command::State> state_{command::State::starting};
  std::atomic<int> requests_{0};
  command::Arbiter arbiter_{2000ms, {}};
  std::optional<MqttProbe> plant_probe_, mes_probe_;  // once the broker is up
  std::unique_ptr<plant_link::PlantLink> link_;
};

TEST_F(PlantPayloadPin, EveryPayloadIsPinned) {
  feed(0.0, Command{"start", Text::format("cellctl run")});
  feed(0.0, RunStarted{"pinned", "demo-cell", "virtual-time", 2});
  feed(0.0, StateChanged{"Idle", "Starting", Text::format("start by cellctl run")});
  feed(0.173, StateChanged{"Starting", "Execute", {}});
  feed(0.174, StepStarted{0, "go (line 3)"});
  Sample s;
  s.axes = 2;
  s.planned_mm = {12.3f, -0.00004f};
  s.scu_mm = {12.30006f, 1.5f};
  s.encoder_mm = 12.29f;
  s.encoder_mm_s = 3.33333f;
  s.spindle_set_hz = 400.0f;
  s.spindle_actual_hz = 399.98f;
  feed(0.2, s);
  feed(0.5, StepEnded{0, "go (line 3)", true, {}});
  feed(0.5, StepStarted{1, "wait (line 4)"});
  command("hold", R"({"id":"h1","by":"MES line 2"})", command::State::execute);
  feed(1.2, Command{"hold", Text::format("plant plant/area1/demo-cell/cmd/hold (MES line 2)")});
  feed(1.2, StateChanged{"Execute", "Holding", Text::format("hold by plant")});
  feed(1.3, StateChanged{"Holding", "Held", Text::format("cell at rest")});
  feed(1.3, Fault{"operator_stop", 2, Text::format("Ctrl-C")});
  command("reset", R"({"id":"r1"})", command::State::held);
  feed(1.5, Note{Text::format("reset refused: the cause of operator_stop is still present"), false});
  feed(1.6, FaultCleared{"operator_stop"});
  command("unhold", R"({"id":"u1"})", command::State::held);
  feed(1.7, Command{"unhold", Text::format("plant plant/area1/demo-cell/cmd/unhold")});
  feed(1.7, StateChanged{"Held", "Unholding", {}});
  feed(1.8, StateChanged{"Unholding", "Execute", {}});
  feed(2.0,
       InjectedFault{"scu", "silent", "scu:silent@2+1", "the line carries nothing either way", false, false});
  feed(2.1, Fault{"link_silent", 0, Text::format("scu silent for 301 ms (limit 300 ms)")});
  feed(2.1, StateChanged{"Execute", "Aborting", Text::format("stop category 0")});
  feed(2.2, StepEnded{1, "wait (line 4)", false, Text::format("stopped by the fault")});
  command("abort", R"({"id":"a1"})", command::State::stopping);
  feed(2.3, StateChanged{"Aborting", "Aborted", Text::format("cell at rest")});
  feed(2.3, RunEnded{"aborted"});
  // A start refused at once, a word that is no command, a retained command: answered by the link.
  const auto answered = [&](std::size_t n) {
    ASSERT_TRUE(wait_until([&] { return on("response").size() >= n; }, 10s)) << on("response").size();
  };
  answered(4);
  mes_probe_->publish(std::string(MqttBroker::kPrefix) + "/demo-cell/cmd/start",
                      R"({"recipe":"short","id":7})");
  answered(5);
  mes_probe_->publish(std::string(MqttBroker::kPrefix) + "/demo-cell/cmd/jump", R"({"id":8})");
  answered(6);
  mes_probe_->publish(std::string(MqttBroker::kPrefix) + "/demo-cell/cmd/unhold", R"({"id":9})", true);
  answered(7);
  // The next job, to Complete.
  feed(0.0, RunStarted{"home", "demo-cell", "virtual-time", 1, "homing"});
  feed(0.0, StateChanged{"Idle", "Starting", Text::format("start by plant")});
  feed(0.1, StateChanged{"Starting", "Execute", {}});
  feed(0.2, StepStarted{0, "home x (line 1)"});
  feed(0.9, StepEnded{0, "home x (line 1)", true, {}});
  feed(1.0, StateChanged{"Execute", "Completing", {}});
  feed(1.1, StateChanged{"Completing", "Complete", Text::format("all steps done; home record written")});
  feed(1.1, RunEnded{"complete"});
  ASSERT_TRUE(plant_probe_->wait_for([](const Message& m) {
    return MqttProbe::on(m, "/state") && MqttProbe::body(m)["state"] == "Complete";
  }));
  const auto from = plant_probe_->count();
  const auto status =
      plant_probe_->wait_for([](const Message& m) { return MqttProbe::on(m, "/status"); }, from);
  ASSERT_TRUE(status);
  link_.reset();  // online: false
  ASSERT_TRUE(plant_probe_->wait_for(
      [](const Message& m) { return MqttProbe::on(m, "/online") && MqttProbe::body(m)["online"] == false; }));

  std::map<std::string, std::vector<std::string>> seen;
  for (const char* tag : {"online", "state", "mode", "admin", "response"}) seen[tag] = on(tag);
  // The status's link counters depend on how soon the broker took the link: their keys are pinned.
  auto st = MqttProbe::body(*status);
  for (auto& [k, v] : st["link"].items())
    if (v.is_number()) v = 0;
  seen["status"] = {st.dump()};
  const std::map<std::string, std::vector<std::string>> expected = {
      {"admin",
       {
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":null,"active_faults":[],"faults":0,"runs":0,"steps_done":0,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":null,"active_faults":[],"faults":0,"runs":1,"steps_done":0,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":null,"active_faults":[],"faults":0,"runs":1,"steps_done":1,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":{"command":"hold","source":"plant plant/area1/demo-cell/cmd/hold (MES line 2)","t":1.2,"text":"hold commanded by plant plant/area1/demo-cell/cmd/hold (MES line 2)"},"active_faults":[],"faults":0,"runs":1,"steps_done":1,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":{"category":2,"fault":"operator_stop","t":1.3,"text":"operator_stop: Ctrl-C"},"active_faults":[{"category":2,"rule":"operator_stop","t":1.3,"text":"Ctrl-C"}],"faults":1,"runs":1,"steps_done":1,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":{"category":2,"fault":"operator_stop","t":1.3,"text":"operator_stop: Ctrl-C"},"active_faults":[],"faults":1,"runs":1,"steps_done":1,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":{"category":0,"fault":"link_silent","t":2.1,"text":"link_silent: scu silent for 301 ms (limit 300 ms)"},"active_faults":[{"category":0,"rule":"link_silent","t":2.1,"text":"scu silent for 301 ms (limit 300 ms)"}],"faults":2,"runs":1,"steps_done":1,"steps_failed":0})J",
           R"J({"ProdDefectiveCount":0,"ProdProcessedCount":0,"StopReason":{"step":2,"t":2.2,"text":"step 2 (wait (line 4)) failed: stopped by the fault"},"active_faults":[{"category":0,"rule":"link_silent","t":2.1,"text":"scu silent for 301 ms (limit 300 ms)"}],"faults":2,"runs":1,"steps_done":1,"steps_failed":1})J",
           R"J({"ProdDefectiveCount":1,"ProdProcessedCount":0,"StopReason":{"step":2,"t":2.2,"text":"step 2 (wait (line 4)) failed: stopped by the fault"},"active_faults":[{"category":0,"rule":"link_silent","t":2.1,"text":"scu silent for 301 ms (limit 300 ms)"}],"faults":2,"runs":1,"steps_done":1,"steps_failed":1})J",
           R"J({"ProdDefectiveCount":1,"ProdProcessedCount":0,"StopReason":null,"active_faults":[],"faults":2,"runs":2,"steps_done":1,"steps_failed":1})J",
           R"J({"ProdDefectiveCount":1,"ProdProcessedCount":0,"StopReason":null,"active_faults":[],"faults":2,"runs":2,"steps_done":2,"steps_failed":1})J",
       }},
      {"mode",
       {
           R"J({"UnitModeCurrent":2,"mode":"dry-run virtual time","recipe":""})J",
           R"J({"UnitModeCurrent":2,"mode":"dry-run virtual time","recipe":"pinned"})J",
           R"J({"UnitModeCurrent":2,"mode":"dry-run virtual time","recipe":"home"})J",
       }},
      {"online",
       {
           R"J({"cell":"demo-cell","client_id":"cellctl-under-test","online":true})J",
           R"J({"client_id":"cellctl-under-test","online":false,"reason":"cellctl ended"})J",
       }},
      {"response",
       {
           R"J({"command":"hold","id":"h1","ok":true,"outcome":"accepted at t = 1.200 s","source":"plant plant/area1/demo-cell/cmd/hold (by MES line 2)","t":1.2})J",
           R"J({"command":"reset","id":"r1","ok":false,"reason":"reset refused: the cause of operator_stop is still present","source":"plant plant/area1/demo-cell/cmd/reset","t":1.5})J",
           R"J({"command":"unhold","id":"u1","ok":true,"outcome":"unholding: the interrupted step resumes","source":"plant plant/area1/demo-cell/cmd/unhold","t":1.7})J",
           R"J({"command":"abort","id":"a1","ok":false,"reason":"the run ended before it took the command; see the state tag","source":"plant plant/area1/demo-cell/cmd/abort","t":2.3})J",
           R"J({"command":"start","id":7,"ok":false,"reason":"start is not possible in state Stopping: a job is in progress: Start is taken only in Idle","source":"plant plant/area1/demo-cell/cmd/start"})J",
           R"J({"command":"jump","id":8,"ok":false,"reason":"'jump' is not a command: hold, unhold, stop, abort, reset, clear, start, home or teach-in","source":"plant plant/area1/demo-cell/cmd/jump"})J",
           R"J({"command":"unhold","ok":false,"reason":"a retained unhold from the broker was ignored (plant plant/area1/demo-cell/cmd/unhold): commands are never published with the retain flag (delete it: an empty retained message)","source":"plant plant/area1/demo-cell/cmd/unhold"})J",
       }},
      {"state",
       {
           R"J({"StateCurrent":4,"state":"Idle","t":0.0})J",
           R"J({"StateCurrent":3,"reason":"start by cellctl run","state":"Starting","t":0.0})J",
           R"J({"StateCurrent":6,"state":"Execute","t":0.173})J",
           R"J({"StateCurrent":10,"reason":"hold by plant","state":"Holding","t":1.2})J",
           R"J({"StateCurrent":11,"reason":"cell at rest","state":"Held","t":1.3})J",
           R"J({"StateCurrent":12,"state":"Unholding","t":1.7})J",
           R"J({"StateCurrent":6,"state":"Execute","t":1.8})J",
           R"J({"StateCurrent":8,"reason":"stop category 0","state":"Aborting","t":2.1})J",
           R"J({"StateCurrent":9,"reason":"cell at rest","state":"Aborted","t":2.3})J",
           R"J({"StateCurrent":3,"reason":"start by plant","state":"Starting","t":0.0})J",
           R"J({"StateCurrent":6,"state":"Execute","t":0.1})J",
           R"J({"StateCurrent":16,"state":"Completing","t":1.0})J",
           R"J({"StateCurrent":17,"reason":"all steps done; home record written","state":"Complete","t":1.1})J",
       }},
      {"status",
       {
           R"J({"CurMachSpeed":400.0,"axes":[{"measured_mm":12.3,"name":"x","planned_mm":12.3},{"measured_mm":1.5,"name":"z","planned_mm":0.0}],"encoder_mm":12.29,"jitter_max_us":0.0,"label":"home x (line 1)","link":{"dropped_events":0,"dropped_status":0,"ignored_retained":0,"mqtt":"5","reconnects":0},"progress":1.0,"spindle":{"actual_hz":400.0,"set_hz":400.0},"state":"Complete","step":1,"steps":1,"t":1.1})J",
       }},
  };
  for (const auto& [tag, payloads] : expected) EXPECT_EQ(seen[tag], payloads) << tag;
  std::filesystem::remove_all(dir_);
}

}  // namespace
}  // namespace cellctl::testing
