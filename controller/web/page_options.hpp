#pragma once
// How the operator page is served: where, with which token, over TLS or not, for how many live
// readers, and what it answers to. Filled from the command line (cli/plant_facing.hpp).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "recipe/planned_time.hpp"

namespace cellctl::web {

struct PageOptions {
  std::string address = "127.0.0.1";  // loopback unless asked otherwise
  int port = 8080;
  std::string token;  // for every command, the live events and (unless public) /metrics; never empty
  std::filesystem::path recipes = "recipes";
  std::filesystem::path runs;  // the run records the page lists (cellctl serve's --runs); empty: none
  // Names the page answers to (the Host header) besides the address a client reached it by, and
  // localhost on loopback: a DNS name of the controller (--http-allow-host).
  std::vector<std::string> allowed_hosts;
  std::size_t max_streams = 16;               // live-event readers at once; more are answered 503
  bool public_metrics = false;                // /metrics without the token (--http-public-metrics)
  std::filesystem::path cert_file, key_file;  // both: HTTPS (PEM)
  bool insecure_http = false;                 // plain HTTP on a non-loopback address, as the operator asked
  // Each recipe's planned time on the Start list (recipe_list.hpp); empty: not shown.
  recipe::ProgramTimer plan;

  [[nodiscard]] bool tls() const noexcept { return !cert_file.empty(); }
};

// "ADDR:PORT" or "PORT" (loopback); nullopt with `why` filled when it is neither.
[[nodiscard]] std::optional<PageOptions> parse_listen_address(std::string_view text, std::string& why);

// 127.0.0.0/8, ::1, "localhost".
[[nodiscard]] bool is_loopback(std::string_view address) noexcept;

// Why the page must not be served so (for the command line to refuse it, exit 2), else empty: plain
// HTTP on a non-loopback address without insecure_http (the token and the session would cross the
// plant's network in clear), a certificate without its key or a key without its certificate, a
// stream cap of 0 or over 256.
[[nodiscard]] std::string listen_problem(const PageOptions& options);

}  // namespace cellctl::web
