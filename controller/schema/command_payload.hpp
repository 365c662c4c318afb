#pragma once
// A command's payload as the plant (its broker) and the page (its POST bodies) send it, read at the
// edge into typed fields: bounded before it is parsed (bounded_json.hpp), then each field taken in its
// own type only. What a field means, and which command takes it, is the command desk's
// (plant_link/command_desk.hpp); past this reader nothing in the process holds the payload's JSON.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace cellctl::schema {

// The sender's id for its answer, echoed as it was sent: a string of at most kMaxAnswerIdChars, or a
// number (JSON's unsigned, signed and floating kinds kept apart, so that it is echoed in its own digits).
using AnswerId = std::variant<std::monostate, std::string, std::uint64_t, std::int64_t, double>;
inline constexpr std::size_t kMaxAnswerIdChars = 128;

// A field of the payload: whether its key is there, and its value when it has the field's type (given
// without a value: present in another type, which the desk refuses with the field's own words).
template <class T>
struct Field {
  bool given = false;
  std::optional<T> value;
};

struct CommandPayload {
  AnswerId id;                           // "id": null counts as none
  Field<std::string> by;                 // who, recorded with the source
  Field<std::string> issued_at;          // UTC, RFC 3339 (command/order.hpp reads it)
  Field<std::string> recipe;             // start
  Field<std::vector<std::string>> axes;  // home: a list of strings only
  Field<std::string> axis;               // teach-in
  Field<double> distance_mm, from_mm, speed_mm_s;
};

// A command's payload may have this many bytes (the page's bodies are held to it before they are read).
inline constexpr std::size_t kMaxCommandBytes = 64 * 1024;

// The payload's fields, or why it was refused, in words that never echo the input. An empty payload is
// a command without fields.
[[nodiscard]] std::variant<CommandPayload, std::string> read_command_payload(std::string_view text);

}  // namespace cellctl::schema
