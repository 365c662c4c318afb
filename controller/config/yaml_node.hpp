#pragma once
// The one way cellctl reads YAML (cell configs, recipes, emulator set-ups): a node that knows its
// file and its field path, converts with range checks, rejects unknown keys, and turns every
// problem into a ConfigError "file:line:column: field: rule". Load time only; never in the cycle.

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <concepts>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cellctl::config {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string file, int line, int column, std::string field, std::string rule);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] int line() const noexcept { return line_; }
  [[nodiscard]] int column() const noexcept { return column_; }
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& rule() const noexcept { return rule_; }

 private:
  std::string file_;
  int line_;
  int column_;
  std::string field_;
  std::string rule_;
};

class YamlNode {
 public:
  // Parse errors come back as ConfigError with the parser's position.
  static YamlNode load_file(const std::filesystem::path& path);
  static YamlNode load_string(const std::string& text, const std::string& file_label);

  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& file() const noexcept { return *file_; }
  [[nodiscard]] int line() const noexcept { return node_.Mark().line + 1; }
  [[nodiscard]] int column() const noexcept { return node_.Mark().column + 1; }

  [[nodiscard]] bool is_map() const noexcept { return node_.IsMap(); }
  [[nodiscard]] bool is_sequence() const noexcept { return node_.IsSequence(); }
  [[nodiscard]] bool is_scalar() const noexcept { return node_.IsScalar(); }
  [[nodiscard]] bool has(std::string_view key) const;

  // A required child of a map ("missing required field" otherwise).
  [[nodiscard]] YamlNode at(std::string_view key) const;
  [[nodiscard]] std::optional<YamlNode> maybe(std::string_view key) const;
  // The elements of a sequence ("expected a list" otherwise).
  [[nodiscard]] std::vector<YamlNode> items() const;
  // The keys of a map, in file order.
  [[nodiscard]] std::vector<std::string> keys() const;
  // Fails on the first key in neither list, naming the closest allowed one when it looks like a typo.
  void only_keys(std::initializer_list<std::string_view> allowed,
                 std::span<const std::string_view> also = {}) const;

  [[nodiscard]] std::string as_string() const;
  [[nodiscard]] bool as_bool() const;
  [[nodiscard]] double as_double() const;
  [[nodiscard]] long long as_integer() const;

  template <std::integral T>
  [[nodiscard]] T as_int() const {
    return static_cast<T>(as_integer_in(static_cast<long long>(std::numeric_limits<T>::min()),
                                        static_cast<long long>(std::numeric_limits<T>::max())));
  }
  [[nodiscard]] long long as_integer_in(long long min, long long max) const;
  [[nodiscard]] double as_double_in(double min, double max) const;
  // One of the listed words; the message lists them.
  [[nodiscard]] std::string as_choice(std::initializer_list<std::string_view> choices) const;

  // Shorthands for a child: required, or the fallback when the key is absent.
  [[nodiscard]] std::string string_at(std::string_view key) const { return at(key).as_string(); }
  [[nodiscard]] double double_in(std::string_view key, double min, double max) const {
    return at(key).as_double_in(min, max);
  }
  [[nodiscard]] double double_in_or(std::string_view key, double min, double max, double fallback) const;
  template <std::integral T>
  [[nodiscard]] T int_in_or(std::string_view key, T min, T max, T fallback) const {
    const auto n = maybe(key);
    return n ? static_cast<T>(n->as_integer_in(min, max)) : fallback;
  }
  // A whole number of milliseconds ("…_ms" keys) in [min, max], as a duration.
  [[nodiscard]] std::chrono::nanoseconds milliseconds_or(std::string_view key, long long min, long long max,
                                                         std::chrono::nanoseconds fallback) const {
    const auto n = maybe(key);
    return n ? std::chrono::milliseconds(n->as_integer_in(min, max)) : fallback;
  }
  template <std::integral T>
  [[nodiscard]] T int_in(std::string_view key, T min, T max) const {
    return static_cast<T>(at(key).as_integer_in(min, max));
  }
  [[nodiscard]] bool bool_or(std::string_view key, bool fallback) const;
  [[nodiscard]] std::string string_or(std::string_view key, std::string fallback) const;
  // A file or folder the config names. One rule for every path in a config: relative to the folder
  // of the config file (so a config works wherever cellctl runs from, and a section pasted from
  // config/examples/ means the same in any config beside it); absolute as written.
  [[nodiscard]] std::filesystem::path as_path() const;
  // as_path() of the child, or the fallback (taken as given) when the key is absent.
  [[nodiscard]] std::filesystem::path path_or(std::string_view key,
                                              const std::filesystem::path& fallback) const;

  // Raises a ConfigError at this node's position for this node's field.
  [[noreturn]] void fail(const std::string& rule) const;

 private:
  YamlNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string field)
      : node_(std::move(node)), file_(std::move(file)), field_(std::move(field)) {}
  [[nodiscard]] std::string child_field(std::string_view key) const;
  [[nodiscard]] std::string scalar_text(const char* what) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string field_;
};

}  // namespace cellctl::config
