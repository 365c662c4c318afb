#pragma once
// JSON from the network (the page's bodies, the broker's payloads) is hostile until bounded: its size
// is checked before anything is read, its depth by a SAX pass that builds nothing (nlohmann's SAX
// parser keeps its own stack, so nothing recurses on the input's depth), and only then is it parsed
// into a tree — a tree no deeper than the limit, which its destructor and dump() can walk safely.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <variant>

namespace cellctl::schema {

struct JsonLimits {
  std::size_t max_bytes = 64 * 1024;
  std::size_t max_depth = 32;  // nested objects and arrays; a flat object is depth 1
};

// The parsed object, or why it was refused (in words, the input never echoed). An empty text is the
// empty object: a command with no fields.
[[nodiscard]] std::variant<nlohmann::json, std::string> parse_bounded_object(std::string_view text,
                                                                             const JsonLimits& limits = {});

}  // namespace cellctl::schema
