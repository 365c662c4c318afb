#pragma once
// The operator page's HTTP(S) server (cpp-httplib), set up so that a stop always gets through and
// nothing a client sends costs more than it must:
//  - its thread pool has max_streams + kCommandWorkers workers: the live-event readers (at most
//    max_streams, each holding a worker for as long as it reads) can never take the workers the
//    commands need;
//  - one request per connection: a refused request's body is never read, its connection is closed
//    (a kept-alive connection would read the unread body as the next request);
//  - short time-outs (2 s for the request to come and to be read, 3 s per write): a client that
//    sends nothing, stops sending or stops reading lets its worker go;
//  - bodies bounded (kMaxBody) a second time, by httplib;
//  - every response, errors included, with the security headers: a Content-Security-Policy that
//    allows nothing but the page's own script, style and endpoints (no inline code), no framing, no
//    caching, no content sniffing, no referrer;
//  - an exception answered 500 without its text (httplib would put it in a header);
//  - with a certificate, HTTPS only (TLS 1.2 or newer).
// Throws std::runtime_error when the certificate or key cannot be used.

#include <cstddef>
#include <memory>

#include "web/page_options.hpp"

namespace httplib {
class Server;
}  // namespace httplib

namespace cellctl::web {

inline constexpr std::size_t kCommandWorkers = 4;

[[nodiscard]] std::unique_ptr<httplib::Server> make_page_server(const PageOptions& options);

}  // namespace cellctl::web
