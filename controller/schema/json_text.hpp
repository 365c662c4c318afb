#pragma once
// The schema's own: text for nlohmann::json, which takes std::string, not views.

#include <string>
#include <string_view>

namespace cellctl::schema {

inline std::string str(std::string_view s) {
  return std::string(s);
}

}  // namespace cellctl::schema
