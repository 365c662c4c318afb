// The broker side as the plant's example configures it (config/examples/mosquitto/, started by
// mqtt_broker.hpp), with the plant link in front of a controller standing by (Idle, no job): nobody
// takes over the controller's session, the link connects over TLS with the plant's CA, a dashboard
// cannot command, a message over the size limit never reaches the link, one the broker lets through
// is refused by the link without harm, and answers say who sent the command and expire.

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "command/arbiter.hpp"
#include "config/cell_config.hpp"
#include "plant_link/link_config.hpp"
#include "plant_link/plant_link.hpp"
#include "plant_test_support.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;
using Message = MqttProbe::Message;

class BrokerSecurityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (std::string("cellctl-broker-") + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    broker_ = std::make_unique<MqttBroker>(dir_ / "broker", broker_options_);
    broker_->start();
    link_config_ = test_link_config(*broker_, cell_.name);
    mes_ = std::make_unique<MqttProbe>(broker_->port(), "mes", MqttBroker::kMesPassword,
                                       std::string(MqttBroker::kPrefix) + "/#");
    ASSERT_EQ(mes_->wait_connack(), 0);
  }
  void TearDown() override {
    link_.reset();
    mes_.reset();
    broker_.reset();
    if (!HasFailure()) std::filesystem::remove_all(dir_);
  }

  std::string topic(const std::string& tag) const { return link_config_.topic(tag); }

  void attach_link() {
    plant_link::RunAccess access;
    access.arbiter = &arbiter_;
    access.status = [] { return std::optional<plant_link::LiveRun>(); };
    access.mode = "virtual-time";
    link_ = std::make_unique<plant_link::PlantLink>(link_config_, cell_, access);
    ASSERT_TRUE(wait_until([&] { return link_->counters().connected; }, 10s)) << "the link never connected";
  }

  // The MES sends cmd/<word> with `payload`; the answer whose id is `id`.
  nlohmann::json command(const std::string& word, const std::string& payload, const std::string& id) {
    const auto from = mes_->count();
    mes_->publish(topic("cmd/" + word), payload);
    const auto a = mes_->wait_for(
        [&](const Message& m) { return m.topic == topic("response") && MqttProbe::body(m)["id"] == id; },
        from, 10s);
    EXPECT_TRUE(a) << "no answer to " << word << " " << id;
    return a ? MqttProbe::body(*a) : nlohmann::json();
  }
  nlohmann::json command(const std::string& word, const std::string& id) {
    return command(word, nlohmann::json{{"id", id}}.dump(), id);
  }
  // The MES stores a retained command on the broker (it sees its own message: stored).
  void store_retained(const std::string& word, const std::string& payload) {
    const auto from = mes_->count();
    mes_->publish(topic("cmd/" + word), payload, true);
    ASSERT_TRUE(mes_->wait_for([&](const Message& m) { return m.topic == topic("cmd/" + word); }, from));
  }
  // No answer so far said ok: nothing was taken.
  void expect_nothing_taken() {
    for (const auto& m : mes_->messages())
      if (m.topic == topic("response")) {
        EXPECT_EQ(MqttProbe::body(m)["ok"], false) << m.payload;
      }
    EXPECT_EQ(arbiter_.counters().taken, 0u);
  }

  std::filesystem::path dir_;
  BrokerOptions broker_options_;  // set before SetUp (in the test's constructor)
  std::unique_ptr<MqttBroker> broker_;
  config::CellConfig cell_ =
      config::load_cell_config(std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
  command::Arbiter arbiter_{2000ms, {}};  // standing by: Idle, no job
  plant_link::LinkConfig link_config_;
  std::unique_ptr<MqttProbe> mes_;
  std::unique_ptr<plant_link::PlantLink> link_;
};

TEST_F(BrokerSecurityTest, ADashboardWithTheControllersClientIdCannotKnockItOff) {
  store_retained("start", R"({"recipe":"short"})");
  attach_link();
  // Without use_username_as_clientid this would close the controller's connection (and the link,
  // back, would be handed whatever the broker had kept for it).
  MqttProbe thief(broker_->port(), "dashboard", MqttBroker::kDashboardPassword, "",
                  {link_config_.client_id, plant_link::MqttVersion::v311});
  ASSERT_EQ(thief.wait_connack(), 0);
  EXPECT_EQ(command("hold", "after")["reason"],
            "hold is not possible in state Idle: hold is taken only in Execute");
  const auto c = link_->counters();
  EXPECT_TRUE(c.connected);
  EXPECT_EQ(c.connects, 1u);
  EXPECT_EQ(c.connection_losses, 0u);
  EXPECT_EQ(c.ignored_retained, 0u) << "MQTT 5: the broker sends the link no stored command";
  expect_nothing_taken();
}

TEST_F(BrokerSecurityTest, TheLinkConnectsOverTlsWithThePlantsCaAndItsOwnCertificate) {
  // The section as a cell config has it, its paths relative to the config file.
  config::CellCore cell = cell_;
  cell.source = dir_ / "cell.yaml";
  const auto yaml = "plant_link:\n  port: " + std::to_string(broker_->tls_port()) +
                    "\n  username: cellctl\n  password_env: CELLCTL_TEST_MQTT_PASSWORD\n  topic_prefix: " +
                    MqttBroker::kPrefix +
                    "\n  tls: {ca_file: broker/certs/ca.crt, cert_file: broker/certs/client.crt, key_file: "
                    "broker/certs/client.key}\n";
  ::setenv("CELLCTL_TEST_MQTT_PASSWORD", "cell-secret", 1);
  link_config_ = plant_link::parse_link_config(
      config::YamlNode::load_string(yaml, cell.source.string()).at("plant_link"), cell);
  ASSERT_TRUE(link_config_.tls);
  EXPECT_EQ(link_config_.tls->ca_file, (dir_ / "broker/certs/ca.crt").string());
  attach_link();
  EXPECT_EQ(command("hold", "over-tls")["ok"], false);  // answered: the link reads and writes over TLS
  EXPECT_EQ(link_->counters().connects, 1u);
}

TEST_F(BrokerSecurityTest, ADashboardCannotCommandAndOversizedMessagesNeverReachTheLink) {
  attach_link();
  MqttProbe dashboard(broker_->port(), "dashboard", MqttBroker::kDashboardPassword, "");
  ASSERT_EQ(dashboard.wait_connack(), 0);
  dashboard.publish(topic("cmd/abort"), R"({"id":"dashboard"})");
  dashboard.publish(topic("cmd/start"), R"({"recipe":"short","id":"dashboard-retained"})", true);
  // Over the example's message_size_limit (65536): the broker forwards nothing.
  mes_->publish(topic("cmd/stop"), R"({"id":"huge","pad":")" + std::string(70000, 'x') + "\"}");
  // The MES's command after them is answered: the link saw that one only.
  EXPECT_EQ(command("abort", "mes")["ok"], true);
  EXPECT_EQ(link_->counters().commands, 1u);
  for (const auto& m : mes_->messages())
    if (m.topic == topic("response")) {
      EXPECT_EQ(MqttProbe::body(m)["id"], "mes") << m.payload;
    }
  EXPECT_EQ(arbiter_.state(), command::State::aborted);
}

class LargeMessageTest : public BrokerSecurityTest {
 protected:
  LargeMessageTest() { broker_options_.message_size_limit = 1024 * 1024; }  // a broker that lets it through
};

TEST_F(LargeMessageTest, AHugeDeeplyNestedCommandIsRefusedAndTheLinkStaysConnected) {
  attach_link();
  const std::string deep = "{\"a\":" + std::string(300000, '[') + std::string(300000, ']') + "}";
  const auto from = mes_->count();
  mes_->publish(topic("cmd/hold"), deep);
  const auto a = mes_->wait_for([&](const Message& m) { return m.topic == topic("response"); }, from, 20s);
  ASSERT_TRUE(a) << "no answer to the 600 KB hold";
  const auto j = MqttProbe::body(*a);
  EXPECT_EQ(j["ok"], false);
  EXPECT_NE(j["reason"].get<std::string>().find("more than the 65536"), std::string::npos) << a->payload;
  EXPECT_EQ(j["source"], "plant " + topic("cmd/hold"));
  EXPECT_LT(a->payload.size(), 600u) << "the payload was echoed";
  EXPECT_EQ(command("hold", "after")["ok"], false);  // still reading, still answering
  const auto c = link_->counters();
  EXPECT_TRUE(c.connected);
  EXPECT_EQ(c.connection_losses, 0u);
}

TEST_F(BrokerSecurityTest, AnswersSayWhoCommandedAndExpireAtTheBrokerAsTheStatusDoes) {
  MqttProbe dashboard(broker_->port(), "dashboard", MqttBroker::kDashboardPassword,
                      std::string(MqttBroker::kPrefix) + "/#", {{}, plant_link::MqttVersion::v5});
  ASSERT_EQ(dashboard.wait_connack(), 0);
  attach_link();
  const auto a = command("hold", R"({"id":"by","by":"MES-7"})", "by");
  EXPECT_EQ(a["source"], "plant " + topic("cmd/hold") + " (by MES-7)") << a.dump();
  const auto response = dashboard.wait_for([](const Message& m) { return MqttProbe::on(m, "/response"); });
  ASSERT_TRUE(response);
  ASSERT_TRUE(response->expiry_s);
  EXPECT_GE(*response->expiry_s, 59u);  // what is left of 60 s when the broker forwards it
  EXPECT_LE(*response->expiry_s, 60u);
  const auto status = dashboard.wait_for([](const Message& m) { return MqttProbe::on(m, "/status"); });
  ASSERT_TRUE(status);
  ASSERT_TRUE(status->expiry_s) << "the status period (100 ms), in whole seconds";
  EXPECT_LE(*status->expiry_s, 1u);
  const auto state = dashboard.wait_for([](const Message& m) { return MqttProbe::on(m, "/state"); });
  ASSERT_TRUE(state);
  EXPECT_FALSE(state->expiry_s) << "a retained tag stays until it is replaced";
  EXPECT_EQ(MqttProbe::body(*status)["link"]["mqtt"], "5");
}

}  // namespace
}  // namespace cellctl::testing
