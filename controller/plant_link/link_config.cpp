#include "plant_link/link_config.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace cellctl::plant_link {
namespace {

// A topic level may not hold MQTT's wildcards or separators of its own making.
void check_topic_text(const config::YamlNode& n, const std::string& text, bool allow_slash) {
  if (text.empty()) n.fail("must not be empty");
  for (const char c : text) {
    if (c == '+' || c == '#' || c == '\0' || (!allow_slash && c == '/'))
      n.fail(fmt::format("'{}' may not hold '+', '#'{}", text, allow_slash ? "" : " or '/'"));
  }
  if (text.front() == '/' || text.back() == '/')
    n.fail(fmt::format("'{}' may not begin or end with '/'", text));
}

std::filesystem::path beside(const std::filesystem::path& config_file, const std::string& path) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : config_file.parent_path() / p;
}

std::string existing_file(const config::YamlNode& n, const std::filesystem::path& config_file) {
  const auto p = beside(config_file, n.as_string());
  std::error_code ec;
  if (!std::filesystem::is_regular_file(p, ec)) n.fail(fmt::format("'{}' is no readable file", p.string()));
  return p.string();
}

std::string read_password(const config::YamlNode& section, const std::filesystem::path& config_file) {
  if (const auto f = section.maybe("password_file")) {
    const auto path = existing_file(*f, config_file);
    std::ifstream in(path);
    std::string line;
    if (!in || !std::getline(in, line)) f->fail(fmt::format("'{}' could not be read", path));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) f->fail(fmt::format("'{}' holds no password on its first line", path));
    return line;
  }
  if (const auto e = section.maybe("password_env")) {
    const auto name = e->as_string();
    const char* value = std::getenv(name.c_str());
    if (!value || !*value) e->fail(fmt::format("the environment variable {} is not set", name));
    return value;
  }
  return {};
}

}  // namespace

LinkConfig parse_link_config(const config::YamlNode& s, const config::CellCore& cell) {
  s.only_keys({"host", "port", "client_id", "username", "password_file", "password_env", "tls",
               "topic_prefix", "status_ms", "keepalive_s", "reconnect_min_ms", "reconnect_max_ms", "recipes",
               "answer_timeout_ms", "mqtt_version"});
  LinkConfig c;
  c.cell = cell.name;
  c.host = s.string_or("host", c.host);
  c.port = s.int_in_or<int>("port", 1, 65535, c.port);
  c.client_id = s.string_or("client_id", "cellctl-" + cell.name);
  if (c.client_id.empty() || c.client_id.size() > 23)
    s.at("client_id").fail("must be 1 to 23 characters (MQTT 3.1.1)");
  if (s.has("password_file") && s.has("password_env"))
    s.at("password_env").fail("give password_file or password_env, not both");
  if (const auto u = s.maybe("username")) {
    c.username = u->as_string();
    c.password = read_password(s, cell.source);
  } else if (s.has("password_file") || s.has("password_env")) {
    (s.has("password_file") ? s.at("password_file") : s.at("password_env"))
        .fail("a password needs a username");
  }
  if (const auto t = s.maybe("tls")) {
    t->only_keys({"ca_file", "cert_file", "key_file"});
    TlsConfig tls;
    tls.ca_file = existing_file(t->at("ca_file"), cell.source);
    if (t->has("cert_file") != t->has("key_file"))
      (t->has("cert_file") ? t->at("cert_file") : t->at("key_file"))
          .fail("cert_file and key_file go together");
    if (const auto n = t->maybe("cert_file")) tls.cert_file = existing_file(*n, cell.source);
    if (const auto n = t->maybe("key_file")) tls.key_file = existing_file(*n, cell.source);
    c.tls = tls;
  }
  if (const auto v = s.maybe("mqtt_version")) {
    const auto text = v->as_string();
    if (text != "5" && text != "3.1.1") v->fail(fmt::format("'{}' must be 5 or \"3.1.1\"", text));
    c.version = text == "5" ? MqttVersion::v5 : MqttVersion::v311;
  }
  if (const auto p = s.maybe("topic_prefix")) {
    c.topic_prefix = p->as_string();
    check_topic_text(*p, c.topic_prefix, true);
  }
  c.status_period = std::chrono::milliseconds(s.int_in_or<int>("status_ms", 10, 60000, 100));
  c.keepalive_s = s.int_in_or<int>("keepalive_s", 5, 3600, c.keepalive_s);
  c.reconnect_min = std::chrono::milliseconds(s.int_in_or<int>("reconnect_min_ms", 10, 60000, 100));
  c.reconnect_max = std::chrono::milliseconds(s.int_in_or<int>("reconnect_max_ms", 10, 600000, 5000));
  if (c.reconnect_max < c.reconnect_min)
    s.at("reconnect_max_ms").fail("must not be shorter than reconnect_min_ms");
  c.answer_timeout = std::chrono::milliseconds(s.int_in_or<int>("answer_timeout_ms", 100, 60000, 2000));
  c.recipes = beside(cell.source, s.string_or("recipes", "../recipes"));
  return c;
}

std::optional<LinkConfig> load_link_config(const config::YamlNode& document, const config::CellCore& cell) {
  const auto section = document.maybe("plant_link");
  if (!section) return std::nullopt;
  return parse_link_config(*section, cell);
}

}  // namespace cellctl::plant_link
