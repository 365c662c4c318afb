// `cellctl serve --virtual-time` as the plant uses it, over Debian's mosquitto: the real binary stands
// by with its plant link, and an MES client (user operator) starts homing, recipes and a Teach-In on
// cmd/<word>, one at a time, and commands the job in progress. Every wait is on a message with a
// time-out; no step depends on how fast virtual time runs on a loaded machine, except that a recipe
// dwelling 3600 s of virtual time is still running when the stop that follows its Execute arrives.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "plant_test_support.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;
using Message = MqttProbe::Message;

class ServeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("cellctl-serve-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "recipes");
    broker_ = std::make_unique<MqttBroker>(dir_ / "broker", broker_options_);
    broker_->start();
    config_ = write_cell_with_plant_link(dir_, *broker_, "cellctl-serving", dir_ / "recipes");
    std::filesystem::copy_file(std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/cli/short.yaml",
                               dir_ / "recipes/short.yaml");
    std::filesystem::copy_file(std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/cli/bad-recipe.yaml",
                               dir_ / "recipes/bad-recipe.yaml");
    std::ofstream(dir_ / "recipes/long.yaml") << R"(recipe: {name: long, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
steps:
  - name: an hour
    dwell: 3600
)";
    plant_ = std::make_unique<MqttProbe>(broker_->port(), "mes", MqttBroker::kMesPassword,
                                         std::string(MqttBroker::kPrefix) + "/demo-cell/#");
    ASSERT_EQ(plant_->wait_connack(), 0);
  }

  // cellctl serve --virtual-time with its records in the test's folder (`runs`: another folder for them),
  // online on the broker.
  void launch(const std::filesystem::path& runs = {}, const std::string& fault = {}) {
    const auto runs_dir = runs.empty() ? dir_ / "runs" : runs;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // a test killed by its time-out takes cellctl serve with it
      const auto out = (dir_ / "serve.out").string();
      if (!::freopen("/dev/null", "r", stdin) || !::freopen(out.c_str(), "w", stdout)) ::_exit(126);
      const auto state = (dir_ / "state").string();
      if (fault.empty())
        ::execl(CELLCTL_BINARY, CELLCTL_BINARY, "-c", config_.c_str(), "serve", "--virtual-time", "--runs",
                runs_dir.c_str(), "--state-dir", state.c_str(), static_cast<char*>(nullptr));
      else
        ::execl(CELLCTL_BINARY, CELLCTL_BINARY, "-c", config_.c_str(), "serve", "--virtual-time", "--runs",
                runs_dir.c_str(), "--state-dir", state.c_str(), "--fault", fault.c_str(),
                static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ASSERT_TRUE(plant_->wait_for(
        [](const Message& m) { return m.topic == topic("online") && MqttProbe::body(m)["online"] == true; },
        0, 30s))
        << "cellctl serve never came online:\n"
        << output();
  }

  void TearDown() override {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    plant_.reset();
    broker_.reset();
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }

  static std::string topic(const std::string& tag) {
    return std::string(MqttBroker::kPrefix) + "/demo-cell/" + tag;
  }
  std::string output() const {
    std::ifstream in(dir_ / "serve.out");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  // Sends cmd/<word> with `fields` and an id; the response to it.
  nlohmann::json command(const std::string& word, nlohmann::json fields, const std::string& id) {
    fields["id"] = id;
    const auto from = plant_->count();
    plant_->publish(topic("cmd/" + word), fields.dump());
    const auto r = plant_->wait_for(
        [&](const Message& m) { return m.topic == topic("response") && MqttProbe::body(m)["id"] == id; },
        from, 20s);
    EXPECT_TRUE(r) << "no response to " << word << " " << id << "; cellctl said:\n" << output();
    return r ? MqttProbe::body(*r) : nlohmann::json();
  }
  // The first state tag from message `from` on that says `state`.
  std::optional<nlohmann::json> state_after(std::size_t from, const std::string& state,
                                            std::chrono::milliseconds timeout = 60s) {
    const auto found = plant_->wait_for(
        [&](const Message& m) { return m.topic == topic("state") && MqttProbe::body(m)["state"] == state; },
        from, timeout);
    if (!found) return std::nullopt;
    return MqttProbe::body(*found);
  }
  // cellctl serve ends with 0 and says goodbye on the online tag (after message `from`).
  void expect_clean_end(std::size_t from) {
    int status = 0;
    const auto until = std::chrono::steady_clock::now() + 30s;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      ASSERT_LT(std::chrono::steady_clock::now(), until) << "cellctl serve did not end:\n" << output();
      std::this_thread::sleep_for(10ms);
    }
    pid_ = -1;
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output();
    EXPECT_TRUE(plant_->wait_for(
        [](const Message& m) {
          return m.topic == topic("online") && MqttProbe::body(m)["reason"] == "cellctl ended";
        },
        from, 10s));
  }
  nlohmann::json last_admin() {
    nlohmann::json a;
    for (const auto& m : plant_->messages())
      if (m.topic == topic("admin")) a = MqttProbe::body(m);
    return a;
  }
  // A reset the cell takes: answered ok, the state tag at Idle.
  void reset(const std::string& id) {
    const auto from = plant_->count();
    const auto a = command("reset", {}, id);
    EXPECT_EQ(a["ok"], true) << a.dump();
    EXPECT_TRUE(state_after(from, "Idle", 10s)) << "no Idle after reset " << id << ":\n" << output();
  }
  static std::string read_file(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static bool has(const nlohmann::json& j, const char* key, const std::string& part) {
    return j.contains(key) && j[key].is_string() && j[key].get<std::string>().find(part) != std::string::npos;
  }

  std::filesystem::path dir_;
  std::filesystem::path config_;
  BrokerOptions broker_options_;  // set before SetUp (in the test's constructor)
  std::unique_ptr<MqttBroker> broker_;
  std::unique_ptr<MqttProbe> plant_;
  pid_t pid_ = -1;
};

TEST_F(ServeTest, ThePlantStartsHomingRecipesAndATeachInOneAtATime) {
  launch();
  ASSERT_TRUE(state_after(0, "Idle", 10s)) << "no retained Idle state at the birth";

  // Nothing runs: a command has nothing to act on, and says so.
  auto a = command("hold", {}, "h0");
  EXPECT_EQ(a["ok"], false);
  EXPECT_TRUE(has(a, "reason", "hold is not possible in state Idle")) << a.dump();

  // Homing: started at once, run to Complete, the home record written.
  auto from = plant_->count();
  a = command("home", {}, "home1");
  ASSERT_EQ(a["ok"], true) << a.dump();
  EXPECT_TRUE(has(a, "outcome", "started: homing")) << a.dump();
  ASSERT_TRUE(state_after(from, "Complete")) << output();
  // Complete is told once the job's work is saved (issue 22): the home record is there already.
  EXPECT_TRUE(std::filesystem::exists(dir_ / "state/home.virtual-time.json")) << output();

  // PackML: Complete takes no start; a reset brings the cell to Idle.
  a = command("start", {{"recipe", "long"}}, "early");
  EXPECT_EQ(a["ok"], false) << a.dump();
  EXPECT_TRUE(has(a, "reason", "start is not possible in state Complete: reset first")) << a.dump();
  reset("r1");

  // Idle: the status carries the positions the homing left, to the SCU's resolution (0.1 mm here).
  const auto idle = plant_->wait_for(
      [](const Message& m) { return m.topic == topic("status") && MqttProbe::body(m)["state"] == "Idle"; },
      plant_->count(), 10s);
  ASSERT_TRUE(idle) << output();
  const auto idle_status = MqttProbe::body(*idle);
  ASSERT_TRUE(idle_status["axes"][0].contains("measured_mm")) << idle->payload;
  EXPECT_FALSE(has_long_fraction(idle->payload)) << "unrounded: " << idle->payload;

  // A long recipe: while it runs, a second start is refused with the reason; a stop ends it.
  from = plant_->count();
  a = command("start", {{"recipe", "long"}}, "long1");
  ASSERT_EQ(a["ok"], true) << a.dump();
  const auto starting = state_after(from, "Starting");
  ASSERT_TRUE(starting) << output();
  EXPECT_EQ((*starting)["reason"], "start by plant " + topic("cmd/start")) << "the run names who started it";
  a = command("start", {{"recipe", "short"}}, "busy");
  EXPECT_EQ(a["ok"], false);
  EXPECT_TRUE(has(a, "reason", "a job is in progress: Start is taken only in Idle")) << a.dump();
  ASSERT_TRUE(state_after(from, "Execute")) << output();
  a = command("stop", {}, "stop1");
  EXPECT_EQ(a["ok"], true) << a.dump();
  ASSERT_TRUE(state_after(from, "Stopped")) << output();
  a = command("start", {{"recipe", "short"}}, "stopped");
  EXPECT_TRUE(has(a, "reason", "start is not possible in state Stopped: reset first")) << a.dump();
  reset("r2");

  // A recipe that is not valid for the cell: its problems with their positions, nothing started.
  a = command("start", {{"recipe", "bad-recipe"}}, "bad1");
  EXPECT_EQ(a["ok"], false);
  EXPECT_EQ(a["exit"], 3);
  ASSERT_FALSE(a["errors"].empty()) << a.dump();
  EXPECT_NE(a["errors"][0].get<std::string>().find("bad-recipe.yaml:13:15:"), std::string::npos) << a.dump();

  // A Teach-In, rehearsed: taught, verified, and written into the dry run's copy of the config, which is
  // there when Complete is told; the cell's config is not touched (issue 22: a dry run never writes it).
  const auto config_before = read_file(config_);
  from = plant_->count();
  a = command("teach-in", {{"axis", "x"}, {"distance_mm", 100}, {"from_mm", 5}}, "t1");
  ASSERT_EQ(a["ok"], true) << a.dump();
  const auto taught = state_after(from, "Complete");
  ASSERT_TRUE(taught) << output();
  EXPECT_TRUE(has(*taught, "reason", "total resolution")) << taught->dump();
  EXPECT_NE(read_file(dir_ / "state/config.dry-run.yaml").find("measuring_units: "), std::string::npos)
      << "the dry run's config was not written";
  EXPECT_EQ(read_file(config_), config_before) << "a dry-run Teach-In changed the cell's config";
  EXPECT_FALSE(std::filesystem::exists(config_.string() + ".bak"));

  // Then a recipe on the taught encoder, to Complete.
  reset("r3");
  from = plant_->count();
  a = command("start", {{"recipe", "short"}}, "short1");
  ASSERT_EQ(a["ok"], true) << a.dump();
  ASSERT_TRUE(state_after(from, "Complete")) << output();

  // The counters: four runs (homing, long, Teach-In, short); of the two recipes short was processed,
  // long was stopped (the homing and the Teach-In produce nothing).
  ASSERT_TRUE(plant_->wait_for(
      [](const Message& m) {
        return m.topic == topic("admin") && MqttProbe::body(m)["runs"] == 4 &&
               MqttProbe::body(m)["ProdProcessedCount"] == 1 && MqttProbe::body(m)["ProdDefectiveCount"] == 1;
      },
      0, 10s))
      << last_admin().dump();

  // SIGTERM with no job: a clean end, the goodbye on the online tag.
  from = plant_->count();
  ::kill(pid_, SIGTERM);
  expect_clean_end(from);
  EXPECT_NE(output().find("ended after 4 jobs"), std::string::npos) << output();
}

TEST_F(ServeTest, TheFirstIdleStatusBeforeAnyJobHasTheCellAsItStands) {
  // The emulated x stands at 42 mm (not the 0 the status would show were it not read); nothing moves it.
  auto cell = read_file(config_);
  const auto at = cell.find("start_position_mm: 0");
  ASSERT_NE(at, std::string::npos);
  cell.replace(at, std::string("start_position_mm: 0").size(), "start_position_mm: 42");
  std::ofstream(config_) << cell;
  launch();
  // The first status of all, before any job: the SCU's position, the encoder's (not referenced yet in
  // this fresh plant: it counts from 0) and the axis planned where its best measurement says it
  // stands (the encoder's, as the supervisor plans from), the spindle at rest.
  const auto first = plant_->wait_for([](const Message& m) { return m.topic == topic("status"); }, 0, 10s);
  ASSERT_TRUE(first) << output();
  const auto status = MqttProbe::body(*first);
  EXPECT_EQ(status["state"], "Idle") << first->payload;
  ASSERT_TRUE(status["axes"][0].contains("measured_mm")) << first->payload;
  EXPECT_EQ(status["axes"][0]["measured_mm"], 42.0) << first->payload;
  ASSERT_TRUE(status.contains("encoder_mm")) << first->payload;
  EXPECT_EQ(status["axes"][0]["planned_mm"], status["encoder_mm"]) << first->payload;
  EXPECT_EQ(status["spindle"]["actual_hz"], 0) << first->payload;
  EXPECT_FALSE(has_long_fraction(first->payload)) << "unrounded: " << first->payload;
  EXPECT_NE(output().find("the cell as it stands: x 42.0 mm"), std::string::npos) << output();
  // The look is no job: no run record, no run counted.
  EXPECT_FALSE(std::filesystem::exists(dir_ / "runs")) << output();
  EXPECT_EQ(last_admin().value("runs", -1), 0) << last_admin().dump();
}

TEST_F(ServeTest, SigtermDuringAJobStopsItFirstAndEndsServe) {
  launch();
  const auto from = plant_->count();
  ASSERT_EQ(command("start", {{"recipe", "long"}}, "long1")["ok"], true);
  ASSERT_TRUE(state_after(from, "Execute")) << output();
  ::kill(pid_, SIGTERM);
  // The run's controlled stop is published before the goodbye; serve ends with 0.
  EXPECT_TRUE(state_after(from, "Stopped", 30s)) << output();
  expect_clean_end(from);
  EXPECT_NE(output().find("job 1: Stopped"), std::string::npos) << output();
}

TEST_F(ServeTest, AStopRightAfterAStartIsNeverRefusedAndNothingIsTaught) {
  launch();
  const auto before = read_file(config_);
  const auto from = plant_->count();
  // Slow (2 mm/s over 150 mm: 150 s of virtual time), so that the stop finds it still going on a loaded
  // machine.
  ASSERT_EQ(command("teach-in", {{"axis", "x"}, {"distance_mm", 150}, {"from_mm", 5}, {"speed_mm_s", 2}},
                    "t1")["ok"],
            true);
  // However far the job got — not taken yet, being set up, or running — the stop is taken.
  const auto a = command("stop", {}, "s1");
  ASSERT_EQ(a["ok"], true) << a.dump();
  const auto outcome = a["outcome"].get<std::string>();
  if (outcome.find("cancelled before it started") == std::string::npos) {
    // Taken before the run existed (stopped before any motion) or by the Teach-In's run itself: once
    // its step had begun (Execute), the end says the config is not changed; a run stopped while its
    // devices still started taught nothing and says nothing of it (on a loaded machine the stop can
    // find the run there).
    const auto ended = state_after(from, "Stopped");
    ASSERT_TRUE(ended) << output();
    if (outcome.find("it is stopped before any motion") == std::string::npos &&
        state_after(from, "Execute", 0s)) {
      EXPECT_TRUE(has(*ended, "reason", "is not changed")) << ended->dump();
    }
  }
  // The next start is taken after a reset: the standby is free again.
  reset("r1");
  ASSERT_EQ(command("start", {{"recipe", "short"}}, "after")["ok"], true);
  ASSERT_TRUE(state_after(from, "Complete")) << output();
  EXPECT_EQ(before, read_file(config_)) << "a stopped Teach-In changed the config";
  EXPECT_FALSE(std::filesystem::exists(dir_ / "state/config.dry-run.yaml")) << "nothing was taught";
}

TEST_F(ServeTest, AJobThatLeftADeviceUnknownBlocksEveryStartAfterIt) {
  // The spindle converter's port is lost 1.5 s into every job, with the spindle turning, and stays
  // lost: the run stops, but its stop to the converter can never be confirmed, and nothing bounds a
  // converter's run-down (it has no watchdog): the spindle's safe state is unknown. From then on no job
  // of any kind starts — a recipe, a homing, a Teach-In (issue 21: every job is a run of one cycle).
  std::filesystem::copy_file(
      std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/faults/recipes/spindle_on.yaml",
      dir_ / "recipes/spin.yaml");
  launch({}, "spindle:disconnect@1.5");
  const auto from = plant_->count();
  ASSERT_EQ(command("start", {{"recipe", "spin"}}, "spin1")["ok"], true);
  const auto ended = plant_->wait_for(
      [](const Message& m) {
        const auto state = MqttProbe::body(m).value("state", "");
        return m.topic == topic("state") && (state == "Stopped" || state == "Aborted");
      },
      from, 60s);
  ASSERT_TRUE(ended) << output();
  const bool aborted = MqttProbe::body(*ended)["state"] == "Aborted";
  const auto served = [&] {
    return output().find("job 1: ") != std::string::npos && output().find("UNKNOWN") != std::string::npos;
  };
  ASSERT_TRUE(wait_until(served, 20s)) << output();
  if (aborted) {
    EXPECT_EQ(command("clear", {}, "c1")["ok"], true);
  }
  for (const auto& [word, fields] : {std::pair<std::string, nlohmann::json>{"start", {{"recipe", "short"}}},
                                     {"home", nlohmann::json::object()},
                                     {"teach-in", {{"axis", "x"}, {"distance_mm", 50}, {"from_mm", 5}}}}) {
    // Refused before or after a reset: the cell is not Idle, or the standby is blocked.
    auto a = command(word, fields, word + "-before-reset");
    EXPECT_EQ(a["ok"], false) << a.dump();
  }
  (void)command("reset", {}, "r1");
  for (const auto& [word, fields] : {std::pair<std::string, nlohmann::json>{"start", {{"recipe", "short"}}},
                                     {"home", nlohmann::json::object()},
                                     {"teach-in", {{"axis", "x"}, {"distance_mm", 50}, {"from_mm", 5}}}}) {
    const auto a = command(word, fields, word + "-after-reset");
    EXPECT_EQ(a["ok"], false) << a.dump();
    EXPECT_TRUE(has(a, "reason", "safe state is UNKNOWN since the last job")) << a.dump();
  }
}

TEST_F(ServeTest, AJobThatCannotStartIsPublishedAsAbortedWithItsReason) {
  // Its run record cannot be made: the job is answered "started", then ends Aborted with why.
  launch("/proc/cellctl-no-such-folder");
  const auto from = plant_->count();
  ASSERT_EQ(command("start", {{"recipe", "short"}}, "r1")["ok"], true);
  const auto aborted = state_after(from, "Aborted");
  ASSERT_TRUE(aborted) << output();
  EXPECT_TRUE(has(*aborted, "reason", "not started: ")) << aborted->dump();
  EXPECT_TRUE(has(*aborted, "reason", "cellctl-no-such-folder")) << aborted->dump();

  // PackML: Aborted takes neither a start nor a reset; clear (to Stopped), then reset (to Idle).
  auto a = command("start", {{"recipe", "short"}}, "r2");
  EXPECT_TRUE(has(a, "reason", "start is not possible in state Aborted: clear, then reset")) << a.dump();
  a = command("reset", {}, "reset-too-early");
  EXPECT_EQ(a["ok"], false) << a.dump();
  EXPECT_TRUE(has(a, "reason", "clear first")) << a.dump();
  const auto cleared_from = plant_->count();
  a = command("clear", {}, "c1");
  EXPECT_EQ(a["ok"], true) << a.dump();
  EXPECT_TRUE(state_after(cleared_from, "Stopped", 10s)) << output();
  reset("r3");
  EXPECT_EQ(command("start", {{"recipe", "short"}}, "r4")["ok"], true);
}

TEST_F(ServeTest, EveryCommandSaysWhoSentItAndAnOldOneIsNotObeyed) {
  launch();
  ASSERT_TRUE(state_after(0, "Idle", 10s));
  // Issued three seconds ago by the MES: older than max_command_age_ms (2000), so never started.
  const auto three_s_ago = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now()) - 3;
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&three_s_ago));
  auto a = command("start", {{"recipe", "short"}, {"issued_at", stamp}, {"by", "MES-7"}}, "old");
  EXPECT_EQ(a["ok"], false) << a.dump();
  EXPECT_TRUE(has(a, "reason", "expired: issued")) << a.dump();
  EXPECT_TRUE(has(a, "source", "plant " + topic("cmd/start") + " (by MES-7)")) << a.dump();
  // The same, fresh, is taken, and the job's journal names its source.
  const auto from = plant_->count();
  a = command("start", {{"recipe", "short"}, {"by", "MES-7"}}, "fresh");
  ASSERT_EQ(a["ok"], true) << a.dump();
  ASSERT_TRUE(state_after(from, "Complete")) << output();
  a = command("reset", {{"by", "operator Anna"}}, "reset");
  EXPECT_EQ(a["ok"], true) << a.dump();
  EXPECT_TRUE(has(a, "source", "(by operator Anna)")) << a.dump();
}

// A broker that keeps its retained messages across a restart, as Debian's does.
class ServeRetainedTest : public ServeTest {
 protected:
  ServeRetainedTest() { broker_options_.persistent = true; }

  // A command sent until cellctl serve answers it (a publish before its link has subscribed again
  // reaches no one): anything the broker sent the link on its subscription came before it.
  nlohmann::json answered(const std::string& word, const std::string& id) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const auto tagged = id + "-" + std::to_string(attempt);
      const auto from = plant_->count();
      plant_->publish(topic("cmd/" + word), nlohmann::json{{"id", tagged}}.dump());
      if (const auto a = plant_->wait_for(
              [&](const Message& m) {
                return m.topic == topic("response") && MqttProbe::body(m)["id"] == tagged;
              },
              from, 1s))
        return MqttProbe::body(*a);
    }
    ADD_FAILURE() << "cellctl serve never answered " << word << ":\n" << output();
    return {};
  }
  // No job was started: no state tag left Idle, no answer said ok.
  void expect_no_job() {
    for (const auto& m : plant_->messages()) {
      if (m.topic == topic("state")) {
        EXPECT_EQ(MqttProbe::body(m)["state"], "Idle") << m.payload;
      }
      if (m.topic == topic("response")) {
        EXPECT_EQ(MqttProbe::body(m)["ok"], false) << m.payload;
      }
    }
  }
};

TEST_F(ServeRetainedTest, ARetainedStartIsNeverObeyedAtTheBirthNorAfterABrokerRestart) {
  // Stored before cellctl serve connects (the MES sees its own message: the broker has it).
  plant_->publish(topic("cmd/start"), R"({"recipe":"short","id":"stale","by":"MES-7"})", true);
  ASSERT_TRUE(plant_->wait_for([](const Message& m) { return m.topic == topic("cmd/start"); }));
  launch();
  ASSERT_TRUE(state_after(0, "Idle", 10s));
  EXPECT_EQ(answered("hold", "birth")["ok"], false);
  expect_no_job();

  // A restart for maintenance: the start is still stored; cellctl serve connects again.
  broker_->stop();
  broker_->start();
  plant_ = std::make_unique<MqttProbe>(broker_->port(), "mes", MqttBroker::kMesPassword,
                                       std::string(MqttBroker::kPrefix) + "/demo-cell/#");
  ASSERT_EQ(plant_->wait_connack(), 0);
  EXPECT_EQ(answered("hold", "restarted")["ok"], false);

  // Published retained while cellctl serve listens: refused, and the answer says where it came from.
  const auto from = plant_->count();
  plant_->publish(topic("cmd/start"), R"({"recipe":"short"})", true);
  const auto a = plant_->wait_for(
      [](const Message& m) {
        return m.topic == topic("response") && MqttProbe::body(m)["command"] == "start";
      },
      from, 10s);
  ASSERT_TRUE(a) << output();
  EXPECT_NE(
      MqttProbe::body(*a)["reason"].get<std::string>().find("a retained start from the broker was ignored"),
      std::string::npos)
      << a->payload;
  EXPECT_EQ(MqttProbe::body(*a)["source"], "plant " + topic("cmd/start"));
  // The status counts what it ignored.
  const auto status = plant_->wait_for(
      [](const Message& m) {
        return m.topic == topic("status") && MqttProbe::body(m)["link"]["ignored_retained"] == 1;
      },
      from, 10s);
  EXPECT_TRUE(status) << "the status does not count the ignored retained start";
  expect_no_job();
  EXPECT_EQ(last_admin()["runs"], 0) << last_admin().dump();
}

}  // namespace
}  // namespace cellctl::testing
