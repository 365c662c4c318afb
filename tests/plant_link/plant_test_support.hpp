#pragma once
// What the plant link's tests share: the broker, the probe client, and waiting on a condition.

#include <chrono>
#include <functional>
#include <thread>

#include "mqtt_broker.hpp"
#include "mqtt_probe.hpp"

namespace cellctl::testing {

// Polls `condition` until it holds or `timeout` has passed; true when it held.
inline bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

}  // namespace cellctl::testing
