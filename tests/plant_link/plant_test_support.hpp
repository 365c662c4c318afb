#pragma once
// What the plant link's tests share: the broker, the probe client, and waiting on a condition.

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

#include "mqtt_broker.hpp"
#include "mqtt_probe.hpp"
#include "plant_link/link_config.hpp"

namespace cellctl::testing {

// A number in a payload written with `digits` or more decimals (20.600000381469727): not rounded to its
// resolution. (No std::regex: g++ 12 warns inside it under the asan preset's -O1.)
inline bool has_long_fraction(std::string_view payload, std::size_t digits = 5) {
  for (std::size_t i = 0; i < payload.size(); ++i) {
    if (payload[i] != '.') continue;
    std::size_t n = 0;
    while (i + 1 + n < payload.size() && payload[i + 1 + n] >= '0' && payload[i + 1 + n] <= '9') ++n;
    if (n >= digits) return true;
  }
  return false;
}

// Polls `condition` until it holds or `timeout` has passed; true when it held.
inline bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// Writes `dir`/cell.yaml: the default cell with its encoder EEPROM in `dir` and a plant_link section
// for `broker` (user cellctl, password file in `dir`, status every 100 ms, recipes from `recipes`).
inline std::filesystem::path write_cell_with_plant_link(const std::filesystem::path& dir,
                                                        const MqttBroker& broker,
                                                        const std::string& client_id,
                                                        const std::filesystem::path& recipes) {
  std::ifstream in(std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
  std::stringstream text;
  text << in.rdbuf();
  auto cell = text.str();
  const auto at = cell.find("\n    state_file: ");
  if (at == std::string::npos) throw std::runtime_error("config/cell.yaml has no encoder state_file to move");
  cell.replace(at, cell.find('\n', at + 1) - at, "\n    state_file: " + (dir / "encoder.eeprom").string());
  std::ofstream(dir / "password") << "cell-secret\n";
  cell += "\nplant_link:\n  port: " + std::to_string(broker.port()) + "\n  client_id: " + client_id +
          "\n  username: cellctl\n  password_file: " + (dir / "password").string() +
          "\n  topic_prefix: " + MqttBroker::kPrefix + "\n  status_ms: 100\n  recipes: " + recipes.string() +
          "\n";
  std::ofstream(dir / "cell.yaml") << cell;
  return dir / "cell.yaml";
}

// The link as the tests run it against `broker`: the controller's account, the test prefix, a quick
// back-off (a restarted broker is found again within 200 ms).
inline plant_link::LinkConfig test_link_config(const MqttBroker& broker, const std::string& cell) {
  using namespace std::chrono_literals;
  plant_link::LinkConfig c;
  c.port = broker.port();
  c.cell = cell;
  c.client_id = "cellctl-under-test";
  c.username = "cellctl";
  c.password = "cell-secret";
  c.topic_prefix = MqttBroker::kPrefix;
  c.reconnect_min = 20ms;
  c.reconnect_max = 200ms;
  return c;
}

}  // namespace cellctl::testing
