#include "support/http_get.hpp"

#include <httplib.h>

namespace cellctl::testing {

std::optional<std::pair<int, std::string>> http_get(int port, const std::string& path,
                                                    const std::string& bearer_token) {
  httplib::Client client("127.0.0.1", port);
  const auto r = client.Get(path, {{"Authorization", "Bearer " + bearer_token}});
  if (!r) return std::nullopt;
  return std::pair{r->status, r->body};
}

}  // namespace cellctl::testing
