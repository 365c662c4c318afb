// The plant link around whole virtual-time runs (plant_link_fixture.hpp): the tags a run publishes,
// commands acting within one status period, who may command, a broker lost and back mid-run.

#include "plant_link_fixture.hpp"

namespace cellctl::testing {
namespace {

using Message = MqttProbe::Message;

TEST_F(PlantLinkTest, AVirtualTimeRunPublishesStateStatusAndAdmin) {
  load_recipe(source_dir() / "tests/cli/short.yaml");
  MqttProbe plant(broker_->port(), "dashboard", MqttBroker::kDashboardPassword,
                  std::string(MqttBroker::kPrefix) + "/#");
  ASSERT_EQ(plant.wait_connack(), 0);
  attach_link();
  ASSERT_TRUE(plant.wait_for([](const Message& m) { return MqttProbe::on(m, "/online"); }));
  pace();  // status goes out every 100 ms of wall time: paced, the run has some 60 of them
  const auto r = go_in_background_and_wait([&] {
    ASSERT_TRUE(plant.wait_for([&](const Message& m) { return is(m, "state", "state", "Complete"); }));
  });
  EXPECT_EQ(r.final_state, supervisor::State::complete);
  link_.reset();  // the last tags out

  EXPECT_TRUE(plant.wait_for([&](const Message& m) { return is(m, "state", "state", "Execute"); }));
  const auto complete = plant.wait_for([&](const Message& m) { return is(m, "state", "state", "Complete"); });
  ASSERT_TRUE(complete);
  EXPECT_EQ(MqttProbe::body(*complete)["StateCurrent"], 17);
  const auto status = plant.wait_for([](const Message& m) {
    const auto j = MqttProbe::body(m);
    return MqttProbe::on(m, "/status") && j.contains("spindle") &&
           j["spindle"]["actual_hz"].get<double>() > 250.0;
  });
  ASSERT_TRUE(status) << "no status with the spindle at speed";
  const auto s = MqttProbe::body(*status);
  EXPECT_EQ(s["axes"].size(), 2u);
  EXPECT_TRUE(s["axes"][0].contains("planned_mm"));
  EXPECT_TRUE(s["axes"][0].contains("measured_mm"));
  EXPECT_EQ(s["steps"], 6);
  EXPECT_TRUE(s.contains("jitter_max_us"));
  const auto admin = plant.wait_for([](const Message& m) {
    return MqttProbe::on(m, "/admin") && MqttProbe::body(m)["ProdProcessedCount"] == 1;
  });
  ASSERT_TRUE(admin);
  EXPECT_EQ(MqttProbe::body(*admin)["runs"], 1);
  EXPECT_EQ(MqttProbe::body(*admin)["steps_done"], 6);
  const auto mode = plant.wait_for([](const Message& m) { return MqttProbe::on(m, "/mode"); });
  ASSERT_TRUE(mode);
  EXPECT_EQ(MqttProbe::body(*mode)["mode"], "dry-run virtual time");
  const auto bye = plant.wait_for(
      [](const Message& m) { return MqttProbe::on(m, "/online") && MqttProbe::body(m)["online"] == false; });
  ASSERT_TRUE(bye);
  EXPECT_EQ(MqttProbe::body(*bye)["reason"], "cellctl ended");
}

TEST_F(PlantLinkTest, HoldAndStopByMqttActWithinOneStatusPeriod) {
  load_recipe(source_dir() / "tests/cli/short.yaml");
  MqttProbe op(broker_->port(), "mes", MqttBroker::kMesPassword, std::string(MqttBroker::kPrefix) + "/#");
  ASSERT_EQ(op.wait_connack(), 0);
  attach_link();
  pace();
  double sent_after_t = -1.0;  // the cell time of the last status seen before the hold was sent
  const auto r = go_in_background_and_wait([&] {
    const auto seen = op.wait_for([](const Message& m) {
      return MqttProbe::on(m, "/status") && MqttProbe::body(m)["step"].get<int>() >= 2 &&
             MqttProbe::body(m)["state"] == "Execute";
    });
    ASSERT_TRUE(seen);
    sent_after_t = MqttProbe::body(*seen)["t"].get<double>();
    auto from = op.count();
    op.publish(topic("cmd/hold"), R"({"id":"h1"})");
    const auto held = op.wait_for([](const Message& m) { return MqttProbe::on(m, "/response"); }, from);
    ASSERT_TRUE(held);
    auto a = MqttProbe::body(*held);
    EXPECT_EQ(a["id"], "h1");
    ASSERT_EQ(a["ok"], true) << held->payload;
    // The next status after the answer already shows the hold.
    from = op.count();
    auto next = op.wait_for([](const Message& m) { return MqttProbe::on(m, "/status"); }, from, 2s);
    ASSERT_TRUE(next);
    const auto st = MqttProbe::body(*next)["state"].get<std::string>();
    EXPECT_TRUE(st == "Holding" || st == "Held") << st;
    ASSERT_TRUE(op.wait_for([&](const Message& m) { return is(m, "state", "state", "Held"); }));

    from = op.count();
    op.publish(topic("cmd/hold"), R"({"id":"h2"})");  // not allowed in Held: refused with the reason
    const auto again = op.wait_for([](const Message& m) { return MqttProbe::on(m, "/response"); }, from);
    ASSERT_TRUE(again);
    EXPECT_EQ(MqttProbe::body(*again)["ok"], false);
    EXPECT_EQ(MqttProbe::body(*again)["reason"],
              "hold is not possible in state Held: hold is taken only in Execute")
        << again->payload;

    from = op.count();
    op.publish(topic("cmd/stop"), R"({"id":"s1"})");
    const auto stopped = op.wait_for([](const Message& m) { return MqttProbe::on(m, "/response"); }, from);
    ASSERT_TRUE(stopped);
    EXPECT_EQ(MqttProbe::body(*stopped)["ok"], true) << stopped->payload;
    next = op.wait_for([](const Message& m) { return MqttProbe::on(m, "/status"); }, op.count(), 2s);
    ASSERT_TRUE(next);
    const auto st2 = MqttProbe::body(*next)["state"].get<std::string>();
    EXPECT_TRUE(st2 == "Stopping" || st2 == "Stopped") << st2;
  });
  EXPECT_EQ(r.final_state, supervisor::State::stopped);
  const auto commands = events("command");
  ASSERT_GE(commands.size(), 3u);  // start, hold, stop
  EXPECT_EQ(commands[1]["command"], "hold");
  EXPECT_EQ(commands[2]["command"], "stop");
  // The hold acted within one status period (100 ms) of the status the operator saw before sending it:
  // the run is paced to the wall clock, so this is the real round trip probe → broker → link → cycle.
  double holding_t = -1.0;
  for (const auto& s : events("state"))
    if (s["to"] == "Holding") holding_t = s["t"];
  EXPECT_GT(holding_t, sent_after_t);
  EXPECT_LE(holding_t - sent_after_t, 0.1);
}

TEST_F(PlantLinkTest, CommandsFromUnauthenticatedOrUnauthorisedClientsAreRefused) {
  load_recipe(source_dir() / "tests/cli/short.yaml");
  // Without credentials: the broker refuses the connection (CONNACK 5, not authorised).
  MqttProbe anonymous(broker_->port(), "", "", "");
  EXPECT_EQ(anonymous.wait_connack(), 5);
  MqttProbe wrong(broker_->port(), "mes", "guess", "");
  EXPECT_EQ(wrong.wait_connack(), 5);
  // A viewer is authenticated but may not command: the ACL drops its hold. The operator's hold sent
  // after it arrives and is answered, so the viewer's was not merely late: the link saw one command.
  MqttProbe viewer(broker_->port(), "dashboard", MqttBroker::kDashboardPassword,
                   std::string(MqttBroker::kPrefix) + "/#");
  ASSERT_EQ(viewer.wait_connack(), 0);
  MqttProbe op(broker_->port(), "mes", MqttBroker::kMesPassword, topic("response"));
  ASSERT_EQ(op.wait_connack(), 0);
  attach_link();
  pace();
  const auto r = go_in_background_and_wait([&] {
    ASSERT_TRUE(viewer.wait_for([](const Message& m) {
      return MqttProbe::on(m, "/status") && MqttProbe::body(m)["step"].get<int>() >= 2;
    }));
    viewer.publish(topic("cmd/hold"), R"({"id":"viewer"})");
    anonymous.publish(topic("cmd/hold"), R"({"id":"anonymous"})");
    ASSERT_TRUE(
        viewer.wait_for([](const Message& m) { return MqttProbe::on(m, "/status"); }, viewer.count()));
    op.publish(topic("cmd/stop"), R"({"id":"operator"})");
    const auto a = op.wait_for([](const Message& m) { return MqttProbe::on(m, "/response"); });
    ASSERT_TRUE(a);
    EXPECT_EQ(MqttProbe::body(*a)["id"], "operator");
  });
  EXPECT_EQ(r.final_state, supervisor::State::stopped);
  EXPECT_EQ(link_->counters().commands, 1u);
  for (const auto& m : viewer.messages()) {
    if (MqttProbe::on(m, "/response")) {
      EXPECT_EQ(MqttProbe::body(m)["id"], "operator") << m.payload;
    }
  }
  for (const auto& c : events("command")) EXPECT_NE(c["command"], "hold");
}

TEST_F(PlantLinkTest, ABrokerKilledAndRestartedMidRunChangesNothingInTheRun) {
  load_recipe_text(R"(
recipe: {name: long-dwell, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 30}
steps:
  - move: {to: {x: 10}, speed_mm_s: 10}
  - name: long dwell
    dwell: 6
  - move: {to: {x: 2}, speed_mm_s: 10}
)");
  MqttProbe watcher(broker_->port(), "dashboard", MqttBroker::kDashboardPassword,
                    std::string(MqttBroker::kPrefix) + "/#");
  ASSERT_EQ(watcher.wait_connack(), 0);
  attach_link();
  pace();
  std::uint64_t dropped = 0;
  const auto r = go_in_background_and_wait([&] {
    ASSERT_TRUE(watcher.wait_for([](const Message& m) {
      return MqttProbe::on(m, "/status") &&
             MqttProbe::body(m)["label"].get<std::string>().rfind("long dwell", 0) == 0;
    }));
    broker_->kill();
    ASSERT_TRUE(wait_until([&] { return !link_->counters().connected; }, 10s));
    ASSERT_TRUE(wait_until([&] { return link_->counters().dropped_status > 0; }, 10s));
    broker_->start();
    ASSERT_TRUE(wait_until([&] { return link_->counters().connects >= 2; }, 10s)) << "no reconnect";
    dropped = link_->counters().dropped_status;
    // A client new to the restarted broker (which kept nothing) gets the current state, retained,
    // once the link's publish of it has reached the broker. The link counts the connect before it
    // publishes, so a client may subscribe first and get the state live, without the retain flag
    // (seen once under load): each try is a new client, until one gets it retained.
    std::optional<Message> state;
    ASSERT_TRUE(wait_until(
        [&] {
          MqttProbe fresh(broker_->port(), "mes", MqttBroker::kMesPassword, topic("state"));
          if (fresh.wait_connack() != 0) return false;
          state = fresh.wait_for([](const Message& m) { return m.retain; }, 0, 2s);
          return state.has_value();
        },
        20s))
        << "no client got the state retained";
    EXPECT_EQ(MqttProbe::body(*state)["state"], std::string(to_string(run_->status().read().state)));
  });
  EXPECT_EQ(r.final_state, supervisor::State::complete);
  EXPECT_TRUE(events("fault").empty());
  EXPECT_GT(dropped, 0u);
  EXPECT_EQ(link_->counters().connection_losses, 1u);
}

}  // namespace
}  // namespace cellctl::testing
