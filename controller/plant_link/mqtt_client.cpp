#include "plant_link/mqtt_client.hpp"

#include <mosquitto.h>

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

}  // namespace

MqttClient::MqttClient(const MqttOptions& options) : options_(options) {
  init_library();
  mosq_ = mosquitto_new(options_.client_id.c_str(), true, this);
  if (!mosq_)
    throw std::runtime_error("MQTT: the client could not be created: " + error_text(MOSQ_ERR_ERRNO));
  mosquitto_int_option(mosq_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
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
  if (!options_.tls_ca_file.empty())
    must(mosquitto_tls_set(mosq_, options_.tls_ca_file.c_str(), nullptr, or_null(options_.tls_cert_file),
                           or_null(options_.tls_key_file), nullptr),
         "TLS");
  mosquitto_connect_callback_set(mosq_, &MqttClient::connect_cb);
  mosquitto_disconnect_callback_set(mosq_, &MqttClient::disconnect_cb);
  mosquitto_message_callback_set(mosq_, &MqttClient::message_cb);
}

MqttClient::~MqttClient() {
  mosquitto_destroy(mosq_);
}

int MqttClient::connect() {
  if (!connected_once_) {
    const int rc = mosquitto_connect(mosq_, options_.host.c_str(), options_.port, options_.keepalive_s);
    if (rc == MOSQ_ERR_SUCCESS) connected_once_ = true;
    return rc;
  }
  return mosquitto_reconnect(mosq_);
}

int MqttClient::loop(int timeout_ms) {
  return mosquitto_loop(mosq_, timeout_ms, 1);
}

int MqttClient::publish(std::string_view topic, std::string_view payload, int qos, bool retain) {
  const std::string t(topic);
  return mosquitto_publish(mosq_, nullptr, t.c_str(), static_cast<int>(payload.size()), payload.data(), qos,
                           retain);
}

int MqttClient::subscribe(std::string_view pattern, int qos) {
  const std::string p(pattern);
  return mosquitto_subscribe(mosq_, nullptr, p.c_str(), qos);
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

std::string MqttClient::connack_text(int rc) {
  return mosquitto_connack_string(rc);
}

void MqttClient::connect_cb(mosquitto*, void* self, int rc) {
  auto* c = static_cast<MqttClient*>(self);
  if (c->on_connect) c->on_connect(rc);
}

void MqttClient::disconnect_cb(mosquitto*, void* self, int rc) {
  auto* c = static_cast<MqttClient*>(self);
  if (c->on_disconnect) c->on_disconnect(rc);
}

void MqttClient::message_cb(mosquitto*, void* self, const ::mosquitto_message* m) {
  auto* c = static_cast<MqttClient*>(self);
  if (!c->on_message) return;
  MqttMessage msg;
  msg.topic = m->topic ? m->topic : "";
  if (m->payload && m->payloadlen > 0)
    msg.payload.assign(static_cast<const char*>(m->payload), static_cast<std::size_t>(m->payloadlen));
  msg.retain = m->retain;
  c->on_message(msg);
}

}  // namespace cellctl::plant_link
