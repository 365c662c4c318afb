// A retained command is never obeyed (issue 21): a retained unhold stored on the broker before the
// link connects, still stored after the broker restarts (a persistent broker), and one published
// retained while the link listens, against a run the MES has held. In MQTT 5 the broker sends the
// link no stored command at all; in 3.1.1 it does, with the retain flag, and the link refuses it.

#include "plant_link_fixture.hpp"

namespace cellctl::testing {
namespace {

using Message = MqttProbe::Message;
using plant_link::MqttVersion;

class RetainedCommandTest : public PlantLinkTest, public ::testing::WithParamInterface<MqttVersion> {
 protected:
  RetainedCommandTest() { broker_options_.persistent = true; }
  void SetUp() override {
    PlantLinkTest::SetUp();
    link_config_.version = GetParam();
  }

  // Sends cmd/<word> as the MES until the link answers it (a publish before the link has subscribed
  // again reaches no one); the answer. Anything the broker sent the link on its subscription came
  // before it.
  nlohmann::json answered(MqttProbe& mes, const std::string& word, const std::string& id) {
    for (int attempt = 0; attempt < 20; ++attempt) {
      const auto from = mes.count();
      const auto tagged = id + "-" + std::to_string(attempt);
      mes.publish(topic("cmd/" + word), nlohmann::json{{"id", tagged}}.dump());
      const auto a = mes.wait_for(
          [&](const Message& m) {
            return MqttProbe::on(m, "/response") && MqttProbe::body(m)["id"] == tagged;
          },
          from, 1s);
      if (a) return MqttProbe::body(*a);
    }
    ADD_FAILURE() << "the link never answered " << word;
    return {};
  }
};

TEST_P(RetainedCommandTest, ARetainedUnholdIsNeverObeyedBeforeOrAfterABrokerRestart) {
  load_recipe_text(R"(
recipe: {name: held, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 30}
steps:
  - move: {to: {x: 10}, speed_mm_s: 10}
  - name: long dwell
    dwell: 6
)");
  MqttProbe mes(broker_->port(), "mes", MqttBroker::kMesPassword, std::string(MqttBroker::kPrefix) + "/#");
  ASSERT_EQ(mes.wait_connack(), 0);
  // Stored before the link connects (a mistake, or a replay): the MES sees its own message, so the
  // broker has it.
  mes.publish(topic("cmd/unhold"), R"({"id":"stale","by":"MES-7"})", true);
  ASSERT_TRUE(mes.wait_for([&](const Message& m) { return m.topic == topic("cmd/unhold"); }));
  attach_link();
  pace();
  const auto r = go_in_background_and_wait([&] {
    ASSERT_TRUE(mes.wait_for([](const Message& m) {
      return MqttProbe::on(m, "/status") && MqttProbe::body(m)["state"] == "Execute";
    }));
    ASSERT_EQ(answered(mes, "hold", "hold")["ok"], true);
    ASSERT_TRUE(mes.wait_for([&](const Message& m) { return is(m, "state", "state", "Held"); }));
    {
      // A dashboard that subscribes now is handed the state the run went to, retained (the tag as
      // published on the change, not at a connect).
      MqttProbe late(broker_->port(), "dashboard", MqttBroker::kDashboardPassword, topic("state"));
      ASSERT_EQ(late.wait_connack(), 0);
      const auto state = late.wait_for([](const Message& m) { return m.retain; });
      ASSERT_TRUE(state) << "the state tag is not retained";
      EXPECT_EQ(MqttProbe::body(*state)["state"], "Held");
    }

    // A restart for maintenance: the broker keeps the retained unhold; the link connects again.
    broker_->stop();
    ASSERT_TRUE(wait_until([&] { return !link_->counters().connected; }, 10s));
    broker_->start();
    ASSERT_TRUE(wait_until([&] { return link_->counters().connects >= 2; }, 10s)) << "no reconnect";
    MqttProbe mes2(broker_->port(), "mes", MqttBroker::kMesPassword, std::string(MqttBroker::kPrefix) + "/#");
    ASSERT_EQ(mes2.wait_connack(), 0);
    EXPECT_EQ(answered(mes2, "hold", "again")["reason"],
              "hold is not possible in state Held: hold is taken only in Execute");

    if (GetParam() == MqttVersion::v5) {
      // Published retained while the link listens: it arrives with the retain flag as published.
      const auto from = mes2.count();
      mes2.publish(topic("cmd/unhold"), R"({"id":"live"})", true);
      const auto a = mes2.wait_for([](const Message& m) { return MqttProbe::on(m, "/response"); }, from);
      ASSERT_TRUE(a);
      const auto j = MqttProbe::body(*a);
      EXPECT_EQ(j["ok"], false);
      EXPECT_NE(j["reason"].get<std::string>().find("a retained unhold from the broker was ignored"),
                std::string::npos)
          << a->payload;
      EXPECT_EQ(j["source"], "plant " + topic("cmd/unhold"));
    }
    EXPECT_EQ(run_->status().read().state, supervisor::State::held);
    EXPECT_EQ(answered(mes2, "stop", "stop")["ok"], true);
  });
  EXPECT_EQ(r.final_state, supervisor::State::stopped);
  for (const auto& c : events("command")) EXPECT_NE(c["command"], "unhold") << c.dump();
  const auto c = link_->counters();
  EXPECT_EQ(c.connection_losses, 1u);
  // MQTT 5: the broker sent no stored command, the live retained one was refused. 3.1.1: the stored
  // one came at every connect, with the retain flag, and was refused each time.
  EXPECT_EQ(c.ignored_retained, GetParam() == MqttVersion::v5 ? 1u : c.connects);
  EXPECT_EQ(notes_with("a retained unhold from the broker was ignored"), c.ignored_retained);
  EXPECT_EQ(arbiter_->counters().ignored, c.ignored_retained);
}

INSTANTIATE_TEST_SUITE_P(Mqtt, RetainedCommandTest, ::testing::Values(MqttVersion::v5, MqttVersion::v311),
                         [](const auto& p) { return p.param == MqttVersion::v5 ? "v5" : "v311"; });

}  // namespace
}  // namespace cellctl::testing
