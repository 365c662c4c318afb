#include "schema/bounded_json.hpp"

#include <fmt/format.h>

namespace cellctl::schema {
namespace {

// Counts the nesting and stops the parse at the first level beyond the limit; keeps nothing.
class DepthCheck final : public nlohmann::json::json_sax_t {
 public:
  explicit DepthCheck(std::size_t max_depth) : max_(max_depth) {}
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return enter(); }
  bool key(string_t&) override { return true; }
  bool end_object() override { return leave(); }
  bool start_array(std::size_t) override { return enter(); }
  bool end_array() override { return leave(); }
  bool parse_error(std::size_t at, const std::string&, const nlohmann::json::exception&) override {
    error_at_ = at;
    return false;
  }
  [[nodiscard]] bool too_deep() const noexcept { return too_deep_; }
  [[nodiscard]] std::size_t error_at() const noexcept { return error_at_; }

 private:
  bool enter() {
    if (++depth_ > max_) too_deep_ = true;
    return !too_deep_;
  }
  bool leave() {
    --depth_;
    return true;
  }
  std::size_t max_;
  std::size_t depth_ = 0;
  bool too_deep_ = false;
  std::size_t error_at_ = 0;
};

}  // namespace

std::variant<nlohmann::json, std::string> parse_bounded_object(std::string_view text,
                                                               const JsonLimits& limits) {
  if (text.size() > limits.max_bytes)
    return fmt::format("the payload is {} bytes, more than the {} a command may have", text.size(),
                       limits.max_bytes);
  if (text.empty()) return nlohmann::json::object();
  DepthCheck check(limits.max_depth);
  const bool ok = nlohmann::json::sax_parse(text, &check, nlohmann::json::input_format_t::json, false);
  if (check.too_deep())
    return fmt::format("the payload nests deeper than {} levels: refused unread", limits.max_depth);
  if (!ok) return fmt::format("the payload is no JSON (an error at byte {})", check.error_at());
  auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::string("the payload is no JSON object");
  return j;
}

}  // namespace cellctl::schema
