#pragma once
// A thin owner of one libmosquitto client (the only file that includes mosquitto.h): connect and
// reconnect, publish, subscribe, and one network step at a time on the caller's thread, with the
// library's callbacks as std::functions. Not thread-safe: one thread uses it (the plant link's; a
// test's probe).
//
// MQTT 5 by default, for what 3.1.1 cannot say: a subscription that is sent no retained message and
// sees the retain flag as it was published, an expiry on a message, a bound on what the broker may
// send. A broker that answers a version-5 CONNECT "unsupported protocol version" is spoken to in 3.1.1
// from the next attempt on (version() tells which); the caller's checks must then stand alone.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

struct mosquitto;
struct mosquitto_message;
struct mqtt5__property;
using mosquitto_property = mqtt5__property;

namespace cellctl::plant_link {

enum class MqttVersion : std::uint8_t { v311, v5 };

[[nodiscard]] std::string_view to_string(MqttVersion v) noexcept;

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
  MqttVersion version = MqttVersion::v5;
  // The broker's last will: published by the broker when this client goes without a DISCONNECT.
  std::string will_topic;
  std::string will_payload;
};

struct MqttMessage {
  std::string topic;
  std::string payload;
  bool retain = false;
  std::optional<std::uint32_t> expiry_s;  // MQTT 5's message expiry, as the broker forwarded it
};

class MqttClient {
 public:
  // The most a broker may send this client in one packet (MQTT 5's CONNECT maximum packet size): a
  // command is at most 64 KiB (command/bounded_json.hpp); this leaves room for a refusal with a reason
  // of anything up to 1 MiB, and anything larger never reaches the process.
  static constexpr std::uint32_t kMaxIncomingPacket = 1024 * 1024;

  // Throws std::runtime_error when the library refuses the options (a TLS file it cannot use).
  explicit MqttClient(const MqttOptions& options);
  ~MqttClient();
  MqttClient(const MqttClient&) = delete;
  MqttClient& operator=(const MqttClient&) = delete;

  // Called from inside loop().
  std::function<void(int rc)> on_connect;  // rc 0: accepted; else the broker's refusal (reason_text)
  std::function<void(int rc)> on_disconnect;
  std::function<void(const MqttMessage&)> on_message;

  // Opens the TCP connection and sends CONNECT (the CONNACK arrives in loop()), each time with the
  // same will and credentials and a clean session: nothing queued for an earlier connection is ever
  // delivered. 0 or a MOSQ_ERR_* code.
  int connect();
  // Sends and receives what is due, waiting at most timeout_ms for the socket. 0 or a MOSQ_ERR_* code
  // (MOSQ_ERR_NO_CONN / CONN_LOST when the broker is gone).
  int loop(int timeout_ms);
  // `expiry` (MQTT 5; rounded up to whole seconds): the broker discards the message when it could not
  // deliver it within that time. 3.1.1 has no expiry: the message is sent without.
  int publish(std::string_view topic, std::string_view payload, int qos, bool retain,
              std::optional<std::chrono::milliseconds> expiry = std::nullopt);
  // Everything on `pattern`, retained messages included (a dashboard's subscription).
  int subscribe(std::string_view pattern, int qos);
  // Only what is published from now on (MQTT 5: no retained message is sent for the subscription,
  // and the retain flag arrives as the publisher set it, so a retained publish can be told from a
  // live one). In 3.1.1 a plain subscription: stored messages arrive with the retain flag set.
  int subscribe_live(std::string_view pattern, int qos);
  void disconnect();  // a clean DISCONNECT: the broker discards the will
  // Something is still to be sent (the library's queue).
  [[nodiscard]] bool want_write() const;
  // The version of the next (or current) connection.
  [[nodiscard]] MqttVersion version() const noexcept { return version_; }

  [[nodiscard]] static std::string error_text(int rc);
  // The words for a refusal on_connect gave, in the version it came in.
  [[nodiscard]] std::string reason_text(int rc) const;

 private:
  static void connect_cb(mosquitto*, void* self, int rc);
  static void disconnect_cb(mosquitto*, void* self, int rc);
  static void message_cb(mosquitto*, void* self, const ::mosquitto_message* m,
                         const mosquitto_property* props);

  MqttOptions options_;
  MqttVersion version_;
  mosquitto* mosq_ = nullptr;
};

}  // namespace cellctl::plant_link
