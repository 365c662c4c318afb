// A command's payload as the plant's broker and the page's POST bodies deliver it: arbitrary bytes,
// read at the edge (schema/command_payload.hpp) and answered (schema/command_answer.hpp).
// Properties: every input is read or refused in words, never an exception, a crash or a hang; more
// than the limit is refused unread; a refusal is one of the reader's own sentences, never the input; a
// payload that is read is answered with JSON that parses back to its own id, in its own kind, within a
// bounded size.

#include <nlohmann/json.hpp>
#include <string>
#include <variant>

#include "fuzz_input.hpp"
#include "schema/command_answer.hpp"
#include "schema/command_payload.hpp"
#include "targets.hpp"

namespace cellctl::fuzz {

void command_payload(std::span<const std::uint8_t> bytes) {
  const std::string_view text{reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  const auto read = schema::read_command_payload(text);
  if (const auto* why = std::get_if<std::string>(&read)) {
    // One of the reader's own sentences (sizes and byte offsets their only numbers), never the input:
    // a short input may be a piece of one of them, a longer one never fits in it.
    FUZZ_CHECK(why->size() <= 100);
    FUZZ_CHECK(why->starts_with("the payload is ") || why->starts_with("the payload nests deeper than ") ||
               why->starts_with("'id' must be "));
    return;
  }
  FUZZ_CHECK(text.size() <= schema::kMaxCommandBytes);
  const auto& p = std::get<schema::CommandPayload>(read);
  for (const auto* f : {&p.by, &p.issued_at, &p.recipe, &p.axis}) FUZZ_CHECK(f->given || !f->value);
  schema::CommandAnswer a{"start", p.id, false, "a reason", "plant t/cmd/start", 1.0, false, {}, {}};
  const auto answer = schema::answer_payload(a);
  FUZZ_CHECK(answer.size() <= 1024);  // the id is at most 128 characters, escaped at most 6 bytes each
  const auto back = nlohmann::json::parse(answer, nullptr, false);
  FUZZ_CHECK(back.is_object());
  if (std::holds_alternative<std::monostate>(p.id)) {
    FUZZ_CHECK(!back.contains("id"));
    return;
  }
  const auto id = back.find("id");
  FUZZ_CHECK(id != back.end());
  std::visit(
      [&](const auto& v) {
        using V = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<V, std::string>) {
          FUZZ_CHECK(id->is_string() && id->template get<std::string>() == v);
        } else if constexpr (std::is_same_v<V, double>) {
          FUZZ_CHECK(id->is_number_float() && id->template get<double>() == v);
        } else if constexpr (!std::is_same_v<V, std::monostate>) {
          FUZZ_CHECK(id->is_number_integer() && id->template get<V>() == v);
        }
      },
      p.id);
}

}  // namespace cellctl::fuzz
