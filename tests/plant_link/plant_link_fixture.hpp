#pragma once
// The plant link against Debian's mosquitto (mqtt_broker.hpp: the example's configuration on free
// loopback ports), around whole virtual-time runs of the default cell, commanded through one arbiter
// as `cellctl run` has it. Runs that the test talks to while they go on are paced to real time (a
// cycle hook holds virtual time back to the wall clock), so that "within one status period" means
// what it says; every wait is on a condition with a time-out.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "../integration/run_fixture.hpp"
#include "command/arbiter.hpp"
#include "plant_link/link_config.hpp"
#include "plant_link/plant_link.hpp"
#include "plant_test_support.hpp"

namespace cellctl::testing {

using namespace std::chrono_literals;

class PlantLinkTest : public RunFixture {
 protected:
  void SetUp() override {
    RunFixture::SetUp();
    broker_ = std::make_unique<MqttBroker>(dir_ / "broker", broker_options_);
    broker_->start();
    link_config_ = test_link_config(*broker_, cell_.name);
    link_config_.status_period = 100ms;
    link_config_.recipes = source_dir() / "recipes";
  }

  std::string topic(const std::string& tag) const { return link_config_.topic(tag); }

  // The run with the link fed by its journal; the link connected before the run starts.
  void attach_link() {
    auto& run = make_run();
    // As `cellctl run` has it: one arbiter, the run its job from the start.
    command::Tell tell;
    tell.note = [&run](const std::string& words) { run.note_from_operator(words); };  // into the journal
    arbiter_ = std::make_unique<command::Arbiter>(2000ms, std::move(tell));
    arbiter_->attach(run.port());
    (void)arbiter_->start({{}, std::chrono::steady_clock::now(), {}}, [] {
      return command::Taken{command::Taken::How::done, "started"};
    });
    link_ = std::make_unique<plant_link::PlantLink>(
        link_config_, cell_, plant_link::fixed_run(*arbiter_, run.status(), "virtual-time"));
    run.listen(&link_->events());
    ASSERT_TRUE(wait_until([&] { return link_->counters().connected; }, 10s)) << "the link never connected";
  }

  // Virtual time never runs ahead of the wall clock from here on (until pace_ is cleared).
  void pace() {
    pace_.store(true);
    run_->on_cycle([this, start = std::chrono::steady_clock::now()](double t, runtime::CellRun&) {
      if (pace_.load()) std::this_thread::sleep_until(start + std::chrono::duration<double>(t));
    });
  }

  runtime::RunResult go_in_background_and_wait(std::function<void()> during) {
    runtime::RunResult result;
    std::thread runner([&] { result = go(); });
    during();
    pace_.store(false);
    runner.join();
    return result;
  }

  static bool is(const MqttProbe::Message& m, const std::string& tag, const char* key,
                 const std::string& value) {
    if (!MqttProbe::on(m, "/" + tag)) return false;
    const auto j = MqttProbe::body(m);
    return j.is_object() && j.contains(key) && j[key].is_string() && j[key] == value;
  }

  BrokerOptions broker_options_;  // set before SetUp (in the test's constructor)
  std::unique_ptr<MqttBroker> broker_;
  plant_link::LinkConfig link_config_;
  std::unique_ptr<command::Arbiter> arbiter_;  // before the link: the link reaches it until it is gone
  std::unique_ptr<plant_link::PlantLink> link_;
  std::atomic<bool> pace_{false};
};

}  // namespace cellctl::testing
