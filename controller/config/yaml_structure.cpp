#include "config/yaml_structure.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/parser.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include "config/yaml_node.hpp"

namespace cellctl::config {
namespace {

// A mapping or sequence being walked: its field path (as YamlNode names fields), and for a mapping
// whether the next node is a key, the current key and where every key so far was given.
struct Level {
  bool mapping = false;
  std::string field;
  bool expect_key = true;
  std::string key;
  std::size_t index = 0;
  std::map<std::string, YAML::Mark, std::less<>> keys;
};

class StructureCheck final : public YAML::EventHandler {
 public:
  explicit StructureCheck(const std::string& file) : file_(file) {}

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ > 1)
      fail(mark, "", "a second YAML document starts here; a config or recipe file holds one document");
  }
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { value(mark, "null or empty"); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { value(mark, "an alias"); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string& text) override {
    if (expecting_key()) {
      key(mark, text);
      return;
    }
    (void)child_field();  // a scalar value: its parent moves past it, there is nothing to open
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    open(mark, false, "a list");
  }
  void OnSequenceEnd() override { stack_.pop_back(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    open(mark, true, "a mapping");
  }
  void OnMapEnd() override { stack_.pop_back(); }

 private:
  [[nodiscard]] bool expecting_key() const {
    return !stack_.empty() && stack_.back().mapping && stack_.back().expect_key;
  }

  // The field path of the node this event starts, and the parent moved past it.
  std::string child_field() {
    if (stack_.empty()) return "";
    Level& parent = stack_.back();
    if (!parent.mapping) return fmt::format("{}[{}]", parent.field, parent.index++);
    parent.expect_key = true;
    return parent.field.empty() ? parent.key : fmt::format("{}.{}", parent.field, parent.key);
  }

  void key(const YAML::Mark& mark, const std::string& text) {
    Level& map = stack_.back();
    const std::string field = map.field.empty() ? text : fmt::format("{}.{}", map.field, text);
    const auto [it, fresh] = map.keys.try_emplace(text, mark);
    if (!fresh)
      fail(mark, field,
           fmt::format("duplicate key '{}': also given at line {}, column {}; which one is meant?", text,
                       it->second.line + 1, it->second.column + 1));
    map.key = text;
    map.expect_key = false;
  }

  // A non-scalar node: in key position it is refused; elsewhere it is a value.
  void value(const YAML::Mark& mark, const char* what) {
    if (expecting_key())
      fail(mark, stack_.back().field, fmt::format("a key must be a plain name, not {}", what));
    (void)child_field();  // as a scalar value
  }

  void open(const YAML::Mark& mark, bool mapping, const char* what) {
    if (expecting_key())
      fail(mark, stack_.back().field, fmt::format("a key must be a plain name, not {}", what));
    Level level;
    level.mapping = mapping;
    level.field = child_field();
    if (stack_.size() >= static_cast<std::size_t>(kMaxYamlNesting))
      fail(mark, level.field, fmt::format("nested deeper than {} levels", kMaxYamlNesting));
    stack_.push_back(std::move(level));
  }

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& field, const std::string& rule) const {
    throw ConfigError(file_, std::max(mark.line, 0) + 1, std::max(mark.column, 0) + 1, field, rule);
  }

  const std::string& file_;
  int documents_ = 0;
  std::vector<Level> stack_;
};

}  // namespace

void check_yaml_structure(const std::string& text, const std::string& file) {
  std::istringstream stream(text);
  StructureCheck check(file);
  try {
    YAML::Parser parser(stream);
    while (parser.HandleNextDocument(check)) {
    }
  } catch (const YAML::Exception& e) {
    throw ConfigError(file, std::max(e.mark.line, 0) + 1, std::max(e.mark.column, 0) + 1, "",
                      "invalid YAML: " + e.msg);
  }
}

}  // namespace cellctl::config
