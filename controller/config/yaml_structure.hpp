#pragma once
// What yaml-cpp accepts but a cell config or recipe must not contain, found in one pass over the
// parser's events before the document is built: a second document (yaml-cpp would ignore it),
// a key that is not a plain scalar (a list, a mapping, an alias or nothing), a key given twice in
// one mapping (yaml-cpp would silently keep one of them) and nesting deeper than kMaxYamlNesting
// (the check stops the parser's recursion there). Each is a ConfigError at the offending place;
// a duplicate key's message also names where the key was first given.

#include <string>

namespace cellctl::config {

// Deepest legitimate nesting: a recipe with repeats four deep reaches about 17 levels.
inline constexpr int kMaxYamlNesting = 32;

// Throws ConfigError (syntax errors too, with yaml-cpp's position and message).
void check_yaml_structure(const std::string& text, const std::string& file);

}  // namespace cellctl::config
