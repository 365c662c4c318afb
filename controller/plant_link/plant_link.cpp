#include "plant_link/plant_link.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>

#include "plant_link/cell_mirror.hpp"
#include "plant_link/command_desk.hpp"
#include "plant_link/mqtt_client.hpp"
#include "schema/plant_tags.hpp"

namespace cellctl::plant_link {
namespace {

using Clock = std::chrono::steady_clock;

// How long the broker may hold an answer for a subscriber that is away (a persistent session): an MES
// back after a minute learns nothing true from an answer about the cell as it was.
constexpr std::chrono::seconds kAnswerExpiry{60};

bool on_loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

MqttOptions options_of(const LinkConfig& c) {
  MqttOptions o;
  o.host = c.host;
  o.port = c.port;
  o.client_id = c.client_id;
  o.username = c.username;
  o.password = c.password;
  if (c.tls) {
    o.tls_ca_file = c.tls->ca_file;
    o.tls_cert_file = c.tls->cert_file;
    o.tls_key_file = c.tls->key_file;
  }
  o.keepalive_s = c.keepalive_s;
  o.version = c.version;
  o.will_topic = c.topic("online");
  o.will_payload = schema::offline_payload(c.client_id, "connection lost (the broker's last will)");
  return o;
}

}  // namespace

PlantLink::PlantLink(LinkConfig config, const config::CellCore& cell, RunAccess run)
    : config_(std::move(config)), cell_(cell), run_(std::move(run)) {
  (void)MqttClient(options_of(config_));  // options the library refuses fail here, on the caller's thread
  if (!config_.tls && !on_loopback(config_.host))
    spdlog::warn(
        "plant link: no TLS to {}: its password and every command cross the network in clear "
        "(plant_link.tls, config/examples/mosquitto/)",
        config_.host);
  thread_ = std::thread([this] { run_thread(); });
}

PlantLink::~PlantLink() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

LinkCounters PlantLink::counters() const noexcept {
  return {connected_.load(),        connects_.load(),         losses_.load(),
          refused_connects_.load(), events_.dropped(),        dropped_status_.load(),
          commands_.load(),         refused_commands_.load(), ignored_retained_.load()};
}

void PlantLink::run_thread() {
  MqttClient client(options_of(config_));
  CellMirror mirror(cell_, run_.mode);
  CommandDesk desk(cell_, config_.recipes, run_, config_.answer_timeout);
  bool socket = false;
  auto backoff = config_.reconnect_min;
  auto next_attempt = Clock::now();
  auto next_status = Clock::now();
  const std::string cmd_prefix = config_.topic("cmd/");

  const auto publish = [&](std::string_view tag, const std::string& payload, int qos, bool retain,
                           std::optional<std::chrono::milliseconds> expiry = std::nullopt) {
    // Refused only when the connection has just gone: the next connect publishes the retained tags
    // anew and the status goes every period; an answer is lost as it would be with the broker.
    if (connected_.load()) (void)client.publish(config_.topic(tag), payload, qos, retain, expiry);
  };
  // The PackML tags a dashboard must see the moment it subscribes, however late: retained.
  const auto publish_tag = [&](std::string_view tag, const std::string& payload) {
    publish(tag, payload, 1, true);
  };
  const auto publish_retained = [&] {
    publish_tag("online", schema::online_payload(config_.client_id, cell_.name));
    publish_tag("state", schema::state_payload(mirror.state_tag()));
    publish_tag("mode", schema::mode_payload(mirror.mode_tag()));
    publish_tag("admin", schema::admin_payload(mirror.admin_tag()));
  };
  const auto respond = [&](const schema::CommandAnswer& a) {
    if (!a.ok) refused_commands_.fetch_add(1);
    publish("response", schema::answer_payload(a), 1, false, kAnswerExpiry);
  };
  const auto lost = [&](Clock::time_point now) {
    socket = false;
    if (connected_.exchange(false)) losses_.fetch_add(1);
    spdlog::debug("plant link: no connection to {}:{}; next attempt in {} ms", config_.host, config_.port,
                  backoff.count());
    next_attempt = now + backoff;
    backoff = std::min(backoff * 2, config_.reconnect_max);
  };

  auto spoken = client.version();
  client.on_connect = [&](int rc) {
    if (rc != 0) {
      refused_connects_.fetch_add(1);
      spdlog::warn(
          "plant link: the broker {}:{} refused the connection: {}{}", config_.host, config_.port,
          client.reason_text(rc),
          client.version() != spoken ? "; it does not speak MQTT 5: the next attempt speaks 3.1.1" : "");
      spoken = client.version();
      return;  // the library closes the socket; loop() reports it and the back-off applies
    }
    connected_.store(true);
    connects_.fetch_add(1);
    backoff = config_.reconnect_min;
    // Refused only without a connection, and every connect subscribes again (the broker's own refusal
    // comes in its SUBACK).
    (void)client.subscribe_live(config_.topic("cmd/+"), 1);
    publish_retained();
  };
  client.on_disconnect = [&](int) {
    if (connected_.exchange(false)) losses_.fetch_add(1);
  };
  client.on_message = [&](const MqttMessage& m) {
    if (m.topic.rfind(cmd_prefix, 0) != 0) return;
    commands_.fetch_add(1);
    const auto word = std::string_view(m.topic).substr(cmd_prefix.size());
    const command::CommandSource source{
        command::CommandSource::Origin::plant, command::capped(m.topic, 128), {}};
    if (m.retain) {
      // An empty retained message is how a stored one is deleted: no command, nothing to answer.
      if (m.payload.empty()) return;
      // Stored by the broker from some earlier time, or stored for whoever subscribes later: never a
      // command meant now. The link may not clear it (its account cannot write cmd/#): whoever
      // published it must.
      ignored_retained_.fetch_add(1);
      const auto why = fmt::format(
          "a retained {} from the broker was ignored ({}): commands are never "
          "published with the retain flag (delete it: an empty retained message)",
          command::capped(word, 24), source.words());
      run_.arbiter->ignore(why);
      auto a = answer(command::capped(word, 24), {}, false, why);
      a.source = source.words();
      respond(a);
      return;
    }
    if (auto a = desk.submit({word, m.payload, source, Clock::now(), std::nullopt}, mirror.state())) {
      if (a->source.empty()) a->source = source.words();  // a payload refused before its "by" was read
      respond(*a);
    }
  };

  const auto take_events = [&] {
    while (const auto e = events_.pop()) {
      const auto changed = mirror.apply(*e);
      if (changed.state) publish_tag("state", schema::state_payload(mirror.state_tag()));
      if (changed.mode) publish_tag("mode", schema::mode_payload(mirror.mode_tag()));
      if (changed.admin) publish_tag("admin", schema::admin_payload(mirror.admin_tag()));
      for (const auto& a : desk.on_event(*e)) respond(a);
    }
  };
  const auto status = [&] {
    LiveStatus live;
    if (const auto r = run_.status())
      live = {true, r->view.t, r->view.step, r->view.steps, r->label, r->view.jitter_max_us};
    auto tag = mirror.status_tag(live);
    tag.link = schema::StatusTag::Link{connects_.load() > 0 ? connects_.load() - 1 : 0,
                                       dropped_status_.load(), events_.dropped(), ignored_retained_.load(),
                                       std::string(to_string(client.version()))};
    return schema::status_payload(tag);
  };
  // A status is stale after its period: the broker never hands an old one on.
  const auto publish_status = [&] { publish("status", status(), 0, false, config_.status_period); };

  while (!stop_.load()) {
    const auto now = Clock::now();
    take_events();
    for (const auto& a : desk.expire(now)) respond(a);
    if (!socket && now >= next_attempt) {
      const int rc = client.connect();
      if (rc == 0) {
        socket = true;
      } else {
        next_attempt = now + backoff;
        backoff = std::min(backoff * 2, config_.reconnect_max);
      }
    }
    if (now >= next_status) {
      next_status = std::max(next_status + config_.status_period, now);
      if (connected_.load())
        publish_status();
      else
        dropped_status_.fetch_add(1);
    }
    if (socket) {
      if (client.loop(5) != 0) lost(now);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));  // no socket to wait on until next_attempt
    }
  }
  // The end: what the run said last, then a clean goodbye (the broker discards the will).
  take_events();
  for (const auto& a : desk.expire(Clock::time_point::max())) respond(a);
  if (connected_.load()) {
    publish_status();
    publish_tag("online", schema::offline_payload(config_.client_id, "cellctl ended"));
    const auto until = Clock::now() + std::chrono::milliseconds(500);
    while (client.want_write() && Clock::now() < until && client.loop(5) == 0) {
    }
    client.disconnect();
    (void)client.loop(5);  // the DISCONNECT on its way; the link ends whatever the broker does
  }
  connected_.store(false);
}

}  // namespace cellctl::plant_link
