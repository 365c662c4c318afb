#pragma once
// A thin owner of one libmosquitto client (the only file that includes mosquitto.h): connect and
// reconnect, publish, subscribe, and one network step at a time on the caller's thread, with the
// library's callbacks as std::functions. Not thread-safe: one thread uses it (the plant link's; a
// test's probe).

#include <functional>
#include <optional>
#include <string>
#include <string_view>

struct mosquitto;
struct mosquitto_message;

namespace cellctl::plant_link {

struct MqttOptions {
  std::string host = "127.0.0.1";
  int port = 1883;
  std::string client_id;
  std::string username;  // empty: no credentials
  std::string password;
  std::string tls_ca_file;  // empty: no TLS
  std::string tls_cert_file;
  std::string tls_key_file;
  int keepalive_s = 10;
  // The broker's last will: published by the broker when this client goes without a DISCONNECT.
  std::string will_topic;
  std::string will_payload;
};

struct MqttMessage {
  std::string topic;
  std::string payload;
  bool retain = false;
};

class MqttClient {
 public:
  // Throws std::runtime_error when the library refuses the options (a TLS file it cannot use).
  explicit MqttClient(const MqttOptions& options);
  ~MqttClient();
  MqttClient(const MqttClient&) = delete;
  MqttClient& operator=(const MqttClient&) = delete;

  // Called from inside loop().
  std::function<void(int rc)> on_connect;  // rc 0: accepted; else the broker's CONNACK refusal
  std::function<void(int rc)> on_disconnect;
  std::function<void(const MqttMessage&)> on_message;

  // Opens the TCP connection and sends CONNECT (the CONNACK arrives in loop()); the first call
  // connects, later ones reconnect with the same will and credentials. 0 or a MOSQ_ERR_* code.
  int connect();
  // Sends and receives what is due, waiting at most timeout_ms for the socket. 0 or a MOSQ_ERR_* code
  // (MOSQ_ERR_NO_CONN / CONN_LOST when the broker is gone).
  int loop(int timeout_ms);
  int publish(std::string_view topic, std::string_view payload, int qos, bool retain);
  int subscribe(std::string_view pattern, int qos);
  void disconnect();  // a clean DISCONNECT: the broker discards the will
  // Something is still to be sent (the library's queue).
  [[nodiscard]] bool want_write() const;

  [[nodiscard]] static std::string error_text(int rc);
  [[nodiscard]] static std::string connack_text(int rc);

 private:
  static void connect_cb(mosquitto*, void* self, int rc);
  static void disconnect_cb(mosquitto*, void* self, int rc);
  static void message_cb(mosquitto*, void* self, const ::mosquitto_message* m);

  MqttOptions options_;
  mosquitto* mosq_ = nullptr;
  bool connected_once_ = false;
};

}  // namespace cellctl::plant_link
