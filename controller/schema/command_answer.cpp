#include "schema/command_answer.hpp"

#include <nlohmann/json.hpp>

namespace cellctl::schema {

std::string answer_payload(const CommandAnswer& a) {
  nlohmann::json j{{"command", a.command}, {"ok", a.ok}};
  std::visit(
      [&j](const auto& id) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(id)>, std::monostate>) j["id"] = id;
      },
      a.id);
  j[a.ok ? "outcome" : "reason"] = a.text;
  if (!a.source.empty()) j["source"] = a.source;
  if (a.t) j["t"] = *a.t;
  if (a.valid) j["valid"] = true;
  if (a.exit) {
    j["exit"] = *a.exit;
    j["errors"] = a.errors;
  }
  return j.dump();
}

}  // namespace cellctl::schema
