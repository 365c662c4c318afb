#include "plant_link/mqtt_client.hpp"

#include <mosquitto.h>
#include <mqtt_protocol.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace cellctl::plant_link {
namespace {

// mosquitto_lib_init is not thread-safe and must run once before any client.
void init_library() {
  static std::once_flag once;
  std::call_once(once, [] { mosquitto_lib_init(); });
}

const char* or_null(const std::string& s) {
  return s.empty() ? nullptr : s.c_str();
}

int protocol_of(MqttVersion v) {
  return v == MqttVersion::v5 ? MQTT_PROTOCOL_V5 : MQTT_PROTOCOL_V311;
}

// An MQTT 5 property list, freed with its owner.
class Properties {
 public:
  Properties() = default;
  ~Properties() { mosquitto_property_free_all(&list_); }
  Properties(const Properties&) = delete;
  Properties& operator=(const Properties&) = delete;
  void add_int32(int identifier, std::uint32_t value) {
    if (mosquitto_property_add_int32(&list_, identifier, value) != MOSQ_ERR_SUCCESS)
      throw std::runtime_error("MQTT: a property could not be added");
  }
  [[nodiscard]] const mosquitto_property* get() const noexcept { return list_; }

 private:
  mosquitto_property* list_ = nullptr;
};

}  // namespace

std::string_view to_string(MqttVersion v) noexcept {
  return v == MqttVersion::v5 ? "5" : "3.1.1";
}

MqttClient::MqttClient(const MqttOptions& options) : options_(options), version_(options.version) {
  init_library();
  // A clean session: the broker keeps nothing for this client between connections, so a command
  // queued while the link was away is never delivered when it comes back.
  mosq_ = mosquitto_new(options_.client_id.c_str(), true, this);
  if (!mosq_)
    throw std::runtime_error("MQTT: the client could not be created: " + error_text(MOSQ_ERR_ERRNO));
  mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, protocol_of(version_));
  const auto must = [](int rc, const char* what) {
    if (rc != MOSQ_ERR_SUCCESS)
      throw std::runtime_error(std::string("MQTT: ") + what + ": " + error_text(rc));
  };
  if (!options_.username.empty())
    must(mosquitto_username_pw_set(mosq_, options_.username.c_str(), or_null(options_.password)),
         "credentials");
  if (!options_.will_topic.empty())
    must(
        mosquitto_will_set(mosq_, options_.will_topic.c_str(), static_cast<int>(options_.will_payload.size()),
                           options_.will_payload.data(), 1, true),
        "last will");
  if (!options_.tls_ca_file.empty()) {
    must(mosquitto_tls_set(mosq_, options_.tls_ca_file.c_str(), nullptr, or_null(options_.tls_cert_file),
                           or_null(options_.tls_key_file), nullptr),
         "TLS");
    // The broker's certificate is verified (chain and host name); nothing older than TLS 1.2.
    must(mosquitto_tls_opts_set(mosq_, 1, "tlsv1.2", nullptr), "TLS options");
  }
  mosquitto_connect_callback_set(mosq_, &MqttClient::connect_cb);
  mosquitto_disconnect_callback_set(mosq_, &MqttClient::disconnect_cb);
  mosquitto_message_v5_callback_set(mosq_, &MqttClient::message_cb);
}

MqttClient::~MqttClient() {
  mosquitto_destroy(mosq_);
}

int MqttClient::connect() {
  // A full connect every time (not mosquitto_reconnect), so that the CONNECT's properties and the
  // version are those of this attempt.
  mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, protocol_of(version_));
  if (version_ == MqttVersion::v311)
    return mosquitto_connect_bind_v5(mosq_, options_.host.c_str(), options_.port, options_.keepalive_s,
                                     nullptr, nullptr);
  Properties p;
  p.add_int32(MQTT_PROP_MAXIMUM_PACKET_SIZE, kMaxIncomingPacket);
  return mosquitto_connect_bind_v5(mosq_, options_.host.c_str(), options_.port, options_.keepalive_s, nullptr,
                                   p.get());
}

int MqttClient::loop(int timeout_ms) {
  return mosquitto_loop(mosq_, timeout_ms, 1);
}

int MqttClient::publish(std::string_view topic, std::string_view payload, int qos, bool retain,
                        std::optional<std::chrono::milliseconds> expiry) {
  const std::string t(topic);
  Properties p;
  if (expiry && version_ == MqttVersion::v5) {
    const auto seconds = std::chrono::ceil<std::chrono::seconds>(*expiry).count();
    p.add_int32(MQTT_PROP_MESSAGE_EXPIRY_INTERVAL,
                static_cast<std::uint32_t>(std::max<long long>(seconds, 1)));
  }
  return mosquitto_publish_v5(mosq_, nullptr, t.c_str(), static_cast<int>(payload.size()), payload.data(),
                              qos, retain, p.get());
}

int MqttClient::subscribe(std::string_view pattern, int qos) {
  const std::string p(pattern);
  return mosquitto_subscribe_v5(mosq_, nullptr, p.c_str(), qos, 0, nullptr);
}

int MqttClient::subscribe_live(std::string_view pattern, int qos) {
  const std::string p(pattern);
  const int options =
      version_ == MqttVersion::v5 ? MQTT_SUB_OPT_SEND_RETAIN_NEVER | MQTT_SUB_OPT_RETAIN_AS_PUBLISHED : 0;
  return mosquitto_subscribe_v5(mosq_, nullptr, p.c_str(), qos, options, nullptr);
}

void MqttClient::disconnect() {
  mosquitto_disconnect(mosq_);
}

bool MqttClient::want_write() const {
  return mosquitto_want_write(mosq_);
}

std::string MqttClient::error_text(int rc) {
  if (rc == MOSQ_ERR_ERRNO) return std::strerror(errno);
  return mosquitto_strerror(rc);
}

std::string MqttClient::reason_text(int rc) const {
  // 3.1.1's CONNACK codes are 1 to 5; MQTT 5's refusals are 128 and up.
  return rc >= 128 ? mosquitto_reason_string(rc) : mosquitto_connack_string(rc);
}

void MqttClient::connect_cb(mosquitto*, void* self, int rc) {
  auto* c = static_cast<MqttClient*>(self);
  // A 3.1.1 broker answers a version-5 CONNECT "unacceptable protocol version" (3.1.1's code 1, which
  // libmosquitto reports as MQTT 5's 132): the next attempt speaks 3.1.1.
  if (c->version_ == MqttVersion::v5 &&
      (rc == MQTT_RC_UNSUPPORTED_PROTOCOL_VERSION || rc == CONNACK_REFUSED_PROTOCOL_VERSION))
    c->version_ = MqttVersion::v311;
  if (c->on_connect) c->on_connect(rc);
}

void MqttClient::disconnect_cb(mosquitto*, void* self, int rc) {
  auto* c = static_cast<MqttClient*>(self);
  if (c->on_disconnect) c->on_disconnect(rc);
}

void MqttClient::message_cb(mosquitto*, void* self, const ::mosquitto_message* m,
                            const mosquitto_property* props) {
  auto* c = static_cast<MqttClient*>(self);
  if (!c->on_message) return;
  MqttMessage msg;
  msg.topic = m->topic ? m->topic : "";
  if (m->payload && m->payloadlen > 0)
    msg.payload.assign(static_cast<const char*>(m->payload), static_cast<std::size_t>(m->payloadlen));
  msg.retain = m->retain;
  if (std::uint32_t expiry = 0;
      mosquitto_property_read_int32(props, MQTT_PROP_MESSAGE_EXPIRY_INTERVAL, &expiry, false))
    msg.expiry_s = expiry;
  c->on_message(msg);
}

}  // namespace cellctl::plant_link
