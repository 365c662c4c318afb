#include "config/yaml_node.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "config/closest_word.hpp"
#include "config/yaml_structure.hpp"
#include "config/yaml_text.hpp"

namespace cellctl::config {
namespace {

std::string format_number(double v) {
  return fmt::format("{:g}", v);
}

}  // namespace

ConfigError::ConfigError(std::string file, int line, int column, std::string field, std::string rule)
    : std::runtime_error(field.empty() ? fmt::format("{}:{}:{}: {}", file, line, column, rule)
                                       : fmt::format("{}:{}:{}: {}: {}", file, line, column, field, rule)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      field_(std::move(field)),
      rule_(std::move(rule)) {}

YamlNode YamlNode::load_file(const std::filesystem::path& path) {
  return load_string(read_yaml_file(path), path.string());
}

YamlNode YamlNode::load_string(const std::string& text, const std::string& file_label) {
  auto file = std::make_shared<const std::string>(file_label);
  check_yaml_text(text, *file);
  check_yaml_structure(text, *file);
  try {
    return YamlNode(YAML::Load(text), file, "");
  } catch (const YAML::Exception& e) {
    // check_yaml_structure parsed the same text already; kept so that no yaml-cpp error escapes.
    throw ConfigError(*file, std::max(e.mark.line, 0) + 1, std::max(e.mark.column, 0) + 1, "",
                      "invalid YAML: " + e.msg);
  }
}

void YamlNode::fail(const std::string& rule) const {
  // A node made by yaml-cpp for a missing key has no mark; such nodes are never failed on directly.
  throw ConfigError(*file_, std::max(line(), 1), std::max(column(), 1), field_, rule);
}

std::string YamlNode::child_field(std::string_view key) const {
  return field_.empty() ? std::string(key) : fmt::format("{}.{}", field_, key);
}

bool YamlNode::has(std::string_view key) const {
  return node_.IsMap() && node_[std::string(key)].IsDefined();
}

YamlNode YamlNode::at(std::string_view key) const {
  if (!node_.IsMap()) fail("expected a mapping of fields");
  const YAML::Node child = node_[std::string(key)];
  if (!child.IsDefined()) fail(fmt::format("missing required field '{}'", key));
  YamlNode found(child, file_, child_field(key));
  if (child.IsNull()) found.fail("must have a value");
  return found;
}

std::optional<YamlNode> YamlNode::maybe(std::string_view key) const {
  if (!node_.IsMap()) {
    if (node_.IsNull() || !node_.IsDefined()) return std::nullopt;
    fail("expected a mapping of fields");
  }
  const YAML::Node child = node_[std::string(key)];
  if (!child.IsDefined()) return std::nullopt;
  return YamlNode(child, file_, child_field(key));
}

std::vector<YamlNode> YamlNode::items() const {
  if (!node_.IsSequence()) fail("expected a list");
  std::vector<YamlNode> out;
  out.reserve(node_.size());
  for (std::size_t i = 0; i < node_.size(); ++i)
    out.push_back(YamlNode(node_[i], file_, fmt::format("{}[{}]", field_, i)));
  return out;
}

std::vector<std::string> YamlNode::keys() const {
  if (!node_.IsMap()) fail("expected a mapping of fields");
  std::vector<std::string> out;
  for (const auto& kv : node_) out.push_back(kv.first.Scalar());
  return out;
}

void YamlNode::only_keys(std::initializer_list<std::string_view> allowed,
                         std::span<const std::string_view> also) const {
  if (!node_.IsMap()) fail("expected a mapping of fields");
  std::vector<std::string_view> all(allowed);
  all.insert(all.end(), also.begin(), also.end());
  for (const auto& kv : node_) {
    const auto& key = kv.first.Scalar();
    if (std::find(all.begin(), all.end(), key) != all.end()) continue;
    const auto best = closest_word(key, all);
    const YamlNode key_node(kv.first, file_, child_field(key));
    key_node.fail(best.empty() ? std::string("unknown field")
                               : fmt::format("unknown field (did you mean '{}'?)", best));
  }
}

std::string YamlNode::scalar_text(const char* what) const {
  if (!node_.IsScalar()) fail(fmt::format("expected {}", what));
  return node_.Scalar();
}

std::string YamlNode::as_string() const {
  return scalar_text("a text value");
}

bool YamlNode::as_bool() const {
  const auto text = scalar_text("true or false");
  if (text == "true" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "no" || text == "off") return false;
  fail(fmt::format("expected true or false, got '{}'", text));
}

double YamlNode::as_double() const {
  return as_double_in(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
}

long long YamlNode::as_integer() const {
  return as_integer_in(std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
}

// Numbers are checked against their field's range as text is converted, before any arithmetic:
// a value beyond what the conversion can hold is out of the field's range too.
long long YamlNode::as_integer_in(long long min, long long max) const {
  const auto text = scalar_text("a whole number");
  long long v = 0;
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const char* begin = text.data() + (hex ? 2 : 0);
  const auto [end, ec] = std::from_chars(begin, text.data() + text.size(), v, hex ? 16 : 10);
  const bool whole = end == text.data() + text.size() && begin != end && !(hex && *begin == '-');
  if (!whole || (ec != std::errc{} && ec != std::errc::result_out_of_range))
    fail(fmt::format("expected a whole number, got '{}'", text));
  if (ec == std::errc::result_out_of_range || v < min || v > max)
    fail(fmt::format("{} is out of range [{}, {}]", text, min, max));
  return v;
}

double YamlNode::as_double_in(double min, double max) const {
  const auto text = scalar_text("a number");
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  const bool whole = end == text.data() + text.size() && !text.empty();
  if (!whole || (ec != std::errc{} && ec != std::errc::result_out_of_range) || std::isnan(v))
    fail(fmt::format("expected a number, got '{}'", text));
  if (ec == std::errc::result_out_of_range || !std::isfinite(v) || v < min || v > max)
    fail(fmt::format("{} is out of range [{}, {}]", text, format_number(min), format_number(max)));
  return v;
}

std::string YamlNode::as_choice(std::initializer_list<std::string_view> choices) const {
  auto text = as_string();
  if (std::find(choices.begin(), choices.end(), text) != choices.end()) return text;
  fail(fmt::format("'{}' is not one of: {}", text, fmt::join(choices, ", ")));
}

double YamlNode::double_in_or(std::string_view key, double min, double max, double fallback) const {
  const auto n = maybe(key);
  return n ? n->as_double_in(min, max) : fallback;
}

bool YamlNode::bool_or(std::string_view key, bool fallback) const {
  const auto n = maybe(key);
  return n ? n->as_bool() : fallback;
}

std::string YamlNode::string_or(std::string_view key, std::string fallback) const {
  const auto n = maybe(key);
  return n ? n->as_string() : fallback;
}

std::filesystem::path YamlNode::as_path() const {
  const std::filesystem::path p(as_string());
  if (p.empty()) fail("must name a file or folder");
  return p.is_absolute() ? p : std::filesystem::path(*file_).parent_path() / p;
}

std::filesystem::path YamlNode::path_or(std::string_view key, const std::filesystem::path& fallback) const {
  const auto n = maybe(key);
  return n ? n->as_path() : fallback;
}

}  // namespace cellctl::config
