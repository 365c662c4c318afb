#include "schema/command_payload.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "schema/bounded_json.hpp"

namespace cellctl::schema {
namespace {

using nlohmann::json;

template <class T>
Field<T> field(const json& body, const char* key) {
  Field<T> f;
  const auto it = body.find(key);
  if (it == body.end()) return f;
  f.given = true;
  if constexpr (std::is_same_v<T, std::string>) {
    if (it->is_string()) f.value = it->get<std::string>();
  } else if constexpr (std::is_same_v<T, double>) {
    if (it->is_number()) f.value = it->get<double>();
  } else {
    if (!it->is_array()) return f;
    std::vector<std::string> names;
    for (const auto& v : *it) {
      if (!v.is_string()) return f;
      names.push_back(v.get<std::string>());
    }
    f.value = std::move(names);
  }
  return f;
}

// The id in its own kind into `id`; false when it cannot be echoed as sent. (Not a variant of the id and
// a reason: g++ 12 at -O1 and above takes a variant nested in a variant for maybe-uninitialized.)
bool read_id(const json& body, AnswerId& id) {
  const auto it = body.find("id");
  if (it == body.end() || it->is_null()) return true;
  switch (it->type()) {
    case json::value_t::string:
      if (it->get_ref<const std::string&>().size() > kMaxAnswerIdChars) return false;
      id = it->get<std::string>();
      return true;
    case json::value_t::number_unsigned:
      id = it->get<std::uint64_t>();
      return true;
    case json::value_t::number_integer:
      id = it->get<std::int64_t>();
      return true;
    case json::value_t::number_float:
      id = it->get<double>();
      return true;
    default:
      return false;
  }
}

}  // namespace

std::variant<CommandPayload, std::string> read_command_payload(std::string_view text) {
  auto parsed = parse_bounded_object(text, {.max_bytes = kMaxCommandBytes, .max_depth = 32});
  if (auto* why = std::get_if<std::string>(&parsed)) return std::move(*why);
  const auto& body = std::get<json>(parsed);
  CommandPayload p;
  if (!read_id(body, p.id))
    return fmt::format("'id' must be a string of at most {} characters or a number", kMaxAnswerIdChars);
  p.by = field<std::string>(body, "by");
  p.issued_at = field<std::string>(body, "issued_at");
  p.recipe = field<std::string>(body, "recipe");
  p.axes = field<std::vector<std::string>>(body, "axes");
  p.axis = field<std::string>(body, "axis");
  p.distance_mm = field<double>(body, "distance_mm");
  p.from_mm = field<double>(body, "from_mm");
  p.speed_mm_s = field<double>(body, "speed_mm_s");
  return p;
}

}  // namespace cellctl::schema
