#include "web/page_options.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>

#include <charconv>
#include <cstring>

namespace cellctl::web {

std::optional<PageOptions> parse_listen_address(std::string_view text, std::string& why) {
  PageOptions o;
  auto port_text = text;
  if (const auto colon = text.rfind(':'); colon != std::string_view::npos) {
    o.address = std::string(text.substr(0, colon));
    port_text = text.substr(colon + 1);
    if (o.address.empty()) {
      why = "the address before ':' is empty (127.0.0.1:8080, or 8080 for loopback)";
      return std::nullopt;
    }
  }
  int port = 0;
  const auto r = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (r.ec != std::errc() || r.ptr != port_text.data() + port_text.size() || port < 1 || port > 65535) {
    why = fmt::format("'{}' is no port (1 to 65535)", port_text);
    return std::nullopt;
  }
  o.port = port;
  return o;
}

bool is_loopback(std::string_view address) noexcept {
  if (address == "localhost") return true;
  std::string text(address);
  if (text.size() > 2 && text.front() == '[' && text.back() == ']') text = text.substr(1, text.size() - 2);
  in_addr v4{};
  if (inet_pton(AF_INET, text.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  in6_addr v6{};
  return inet_pton(AF_INET6, text.c_str(), &v6) == 1 && std::memcmp(&v6, &in6addr_loopback, sizeof v6) == 0;
}

std::string listen_problem(const PageOptions& o) {
  if (o.cert_file.empty() != o.key_file.empty())
    return "--http-cert and --http-key go together: HTTPS needs the certificate and its private key";
  if (!o.tls() && !is_loopback(o.address) && !o.insecure_http)
    return fmt::format(
        "--http {}: plain HTTP on a non-loopback address would carry the token and the operator's session "
        "across the network in clear; give --http-cert FILE --http-key FILE for HTTPS, or --insecure-http "
        "to serve it so anyway",
        o.address);
  if (o.max_streams < 1 || o.max_streams > 256)
    return fmt::format("--http-streams {}: from 1 to 256 live-event readers", o.max_streams);
  return {};
}

}  // namespace cellctl::web
