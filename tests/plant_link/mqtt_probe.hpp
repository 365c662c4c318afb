#pragma once
// A test's MQTT client (plant_link::MqttClient on a thread of its own): records every message it receives
// and waits on conditions over them with a time-out; publishes on request. MQTT 3.1.1 unless told
// otherwise (as most plant clients still are); its subscription takes retained messages.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "plant_link/mqtt_client.hpp"

namespace cellctl::testing {

struct ProbeOptions {
  std::string client_id;  // empty: probe-<user>-<n>
  plant_link::MqttVersion version = plant_link::MqttVersion::v311;
};

class MqttProbe {
 public:
  using Message = plant_link::MqttMessage;

  MqttProbe(int port, std::string user, std::string password, std::string subscription,
            const ProbeOptions& options = {})
      : subscription_(std::move(subscription)) {
    plant_link::MqttOptions o;
    o.port = port;
    o.client_id =
        options.client_id.empty() ? "probe-" + user + "-" + std::to_string(++serial()) : options.client_id;
    o.username = std::move(user);
    o.password = std::move(password);
    o.version = options.version;
    client_ = std::make_unique<plant_link::MqttClient>(o);
    client_->on_connect = [this](int rc) {
      std::lock_guard lock(mutex_);
      connack_ = rc;
      if (rc == 0 && !subscription_.empty()) (void)client_->subscribe(subscription_, 1);
      changed_.notify_all();
    };
    client_->on_disconnect = [this](int) {
      std::lock_guard lock(mutex_);
      disconnected_ = true;
      changed_.notify_all();
    };
    client_->on_message = [this](const Message& m) {
      std::lock_guard lock(mutex_);
      messages_.push_back(m);
      changed_.notify_all();
    };
    thread_ = std::thread([this] {
      if (client_->connect() != 0) return;
      while (!stop_.load()) {
        std::function<void()> job;
        {
          std::lock_guard lock(mutex_);
          if (!jobs_.empty()) {
            job = std::move(jobs_.front());
            jobs_.erase(jobs_.begin());
          }
        }
        if (job) job();
        if (client_->loop(5) != 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      client_->disconnect();
    });
  }
  ~MqttProbe() {
    stop_.store(true);
    thread_.join();
  }

  // The broker's CONNACK code once it came (0 accepted), nullopt before.
  std::optional<int> wait_connack(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return connack_.has_value(); });
    return connack_;
  }

  void publish(const std::string& topic, const std::string& payload, bool retain = false) {
    std::lock_guard lock(mutex_);
    jobs_.push_back([this, topic, payload, retain] { (void)client_->publish(topic, payload, 1, retain); });
  }
  // The broker closed the connection after it was accepted (taken over, refused a publish).
  bool disconnected() {
    std::lock_guard lock(mutex_);
    return disconnected_;
  }

  // The first message from index `from` on for which pred holds, waiting up to timeout.
  std::optional<Message> wait_for(const std::function<bool(const Message&)>& pred, std::size_t from = 0,
                                  std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
    std::unique_lock lock(mutex_);
    std::optional<Message> found;
    changed_.wait_for(lock, timeout, [&] {
      for (std::size_t i = from; i < messages_.size(); ++i)
        if (pred(messages_[i])) {
          found = messages_[i];
          return true;
        }
      return false;
    });
    return found;
  }
  std::size_t count() {
    std::lock_guard lock(mutex_);
    return messages_.size();
  }
  std::vector<Message> messages() {
    std::lock_guard lock(mutex_);
    return messages_;
  }

  static bool on(const Message& m, const std::string& tag) {
    return m.topic.size() >= tag.size() && m.topic.compare(m.topic.size() - tag.size(), tag.size(), tag) == 0;
  }
  static nlohmann::json body(const Message& m) { return nlohmann::json::parse(m.payload, nullptr, false); }

 private:
  static int& serial() {
    static int n = 0;
    return n;
  }
  std::string subscription_;
  std::unique_ptr<plant_link::MqttClient> client_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Message> messages_;
  std::vector<std::function<void()>> jobs_;
  std::optional<int> connack_;
  bool disconnected_ = false;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace cellctl::testing
