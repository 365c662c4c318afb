#include "web/page_server.hpp"

#include <fmt/format.h>
#include <httplib.h>

#include <chrono>
#include <stdexcept>

#include "schema/page_payloads.hpp"
#include "web/request_guard.hpp"

namespace cellctl::web {
namespace {

using namespace std::chrono_literals;

httplib::Headers security_headers() {
  return {
      {"Content-Security-Policy",
       "default-src 'none'; script-src 'self'; style-src 'self'; connect-src 'self'; img-src 'self'; "
       "base-uri 'none'; form-action 'none'; frame-ancestors 'none'"},
      {"X-Frame-Options", "DENY"},
      {"Cache-Control", "no-store"},
      {"X-Content-Type-Options", "nosniff"},
      {"Referrer-Policy", "no-referrer"},
  };
}

}  // namespace

std::unique_ptr<httplib::Server> make_page_server(const PageOptions& options) {
  std::unique_ptr<httplib::Server> server;
  if (options.tls()) {
    auto tls = std::make_unique<httplib::SSLServer>(options.cert_file.c_str(), options.key_file.c_str());
    if (!tls->is_valid())
      throw std::runtime_error(fmt::format("the operator page's certificate {} or key {} cannot be used",
                                           options.cert_file.string(), options.key_file.string()));
    SSL_CTX_set_min_proto_version(tls->ssl_context(), TLS1_2_VERSION);
    server = std::move(tls);
  } else {
    server = std::make_unique<httplib::Server>();
  }
  const auto workers = options.max_streams + kCommandWorkers;
  server->new_task_queue = [workers] { return new httplib::ThreadPool(workers); };
  server->set_keep_alive_max_count(1);
  server->set_keep_alive_timeout(2);  // a connection that sends no request lets its worker go
  server->set_read_timeout(2s);
  server->set_write_timeout(3s);
  server->set_payload_max_length(kMaxBody);
  server->set_default_headers(security_headers());
  server->set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.status = 500;
    res.set_content(schema::page_reply_json(false, "internal error"), "application/json");
  });
  return server;
}

}  // namespace cellctl::web
