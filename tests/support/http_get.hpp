#pragma once
// One GET on this host's loopback with a bearer token, as a scraper sends it: the status and the body,
// or nullopt when nothing answered. (httplib.h in a source of its own: its macros break Eigen's headers,
// which the run's headers bring in.)

#include <optional>
#include <string>
#include <utility>

namespace cellctl::testing {

[[nodiscard]] std::optional<std::pair<int, std::string>> http_get(int port, const std::string& path,
                                                                  const std::string& bearer_token);

}  // namespace cellctl::testing
