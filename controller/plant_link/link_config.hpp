#pragma once
// The `plant_link:` section of the cell config: how cellctl reaches the plant's MQTT broker (host,
// port, client id, credentials, optional TLS), under which topic prefix it publishes the cell's PackML
// tags, how often it publishes the status, and the folder a `start` command names recipes from.
// The section is called plant_link because `plant:` is the emulated cell's coupling physics.
// Read where the link is built (like the emulators' set-up), from the cell's file as config/ parsed it;
// a bad value is a ConfigError with file:line:column before anything moves.

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>

#include "config/cell_core.hpp"
#include "config/yaml_node.hpp"
#include "plant_link/mqtt_client.hpp"

namespace cellctl::plant_link {

struct TlsConfig {
  std::string ca_file;    // the broker's CA (PEM)
  std::string cert_file;  // client certificate and key, both or neither
  std::string key_file;
};

struct LinkConfig {
  std::string host = "127.0.0.1";
  int port = 1883;
  std::string client_id;  // default cellctl-<cell>
  std::string username;   // empty: connect without credentials
  std::string password;   // read from password_file or the variable password_env names, never the file
  std::optional<TlsConfig> tls;
  // 5 (the default; 3.1.1 from the next attempt when the broker refuses 5), or 3.1.1 pinned.
  MqttVersion version = MqttVersion::v5;
  std::string topic_prefix = "cellctl";
  std::string cell;  // the cell's name: topics are <topic_prefix>/<cell>/…
  std::chrono::milliseconds status_period{100};
  int keepalive_s = 10;
  std::chrono::milliseconds reconnect_min{100};   // back-off doubles from this …
  std::chrono::milliseconds reconnect_max{5000};  // … up to this
  std::filesystem::path recipes = "recipes";      // `start` names a recipe <recipes>/<name>.yaml
  std::chrono::milliseconds answer_timeout{
      2000};  // a command the run has not answered by then is reported so

  [[nodiscard]] std::string topic(std::string_view tag) const {
    return topic_prefix + "/" + cell + "/" + std::string(tag);
  }
};

// Throws config::ConfigError (file:line:column: field: rule). Relative paths are read from the
// config file's folder.
[[nodiscard]] LinkConfig parse_link_config(const config::YamlNode& section, const config::CellCore& cell);
// The section of the cell's file as config/ parsed it (config::CellConfig::document: the file is not
// read again), or nullopt when it has none.
[[nodiscard]] std::optional<LinkConfig> load_link_config(const config::YamlNode& document,
                                                         const config::CellCore& cell);

}  // namespace cellctl::plant_link
