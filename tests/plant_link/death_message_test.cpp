// The plant sees a dead controller: `cellctl run --emulate` with a plant_link section is killed
// (SIGKILL: no goodbye of its own), and the broker publishes its last will, online:false.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "plant_test_support.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;

TEST(PlantLinkDeath, AKilledCellctlLeavesItsLastWillOnTheBroker) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cellctl-plant-death-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  MqttBroker broker(dir / "broker");
  broker.start();

  // The default cell, its encoder EEPROM in the test's folder, with a plant_link section.
  (void)write_cell_with_plant_link(dir, broker, "cellctl-dying", dir);
  std::ofstream(dir / "slow.yaml") << R"(recipe: {name: slow, version: "1", cell: demo-cell}
limits:
  axes:
    x: {min_mm: 0, max_mm: 180, max_speed_mm_s: 18, tolerance_mm: 0.1}
  timeouts: {move_s: 30}
steps:
  - move: {to: {x: 3}, speed_mm_s: 5}
  - dwell: 60
)";

  MqttProbe plant(broker.port(), "dashboard", MqttBroker::kDashboardPassword,
                  std::string(MqttBroker::kPrefix) + "/demo-cell/online");
  ASSERT_EQ(plant.wait_connack(), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const auto cfg = (dir / "cell.yaml").string();
    const auto recipe = (dir / "slow.yaml").string();
    const auto journal = (dir / "run").string();
    if (!::freopen("/dev/null", "r", stdin) || !::freopen((dir / "cellctl.out").c_str(), "w", stdout))
      ::_exit(126);
    ::execl(CELLCTL_BINARY, CELLCTL_BINARY, "-c", cfg.c_str(), "run", recipe.c_str(), "--emulate",
            "--journal", journal.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto birth = plant.wait_for(
      [](const MqttProbe::Message& m) { return MqttProbe::body(m)["online"] == true; }, 0, 30s);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(birth) << "cellctl never came online; its output is in " << (dir / "cellctl.out");
  const auto death = plant.wait_for(
      [](const MqttProbe::Message& m) { return MqttProbe::body(m)["online"] == false; }, 0, 30s);
  ASSERT_TRUE(death) << "no last will after cellctl was killed";
  EXPECT_EQ(MqttProbe::body(*death)["client_id"], "cellctl-dying");
  EXPECT_EQ(MqttProbe::body(*death)["reason"], "connection lost (the broker's last will)");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace cellctl::testing
