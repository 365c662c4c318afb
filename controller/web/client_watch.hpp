#pragma once
// Whether the client of a command being handled is still there: a command whose client has gone is
// not obeyed. httplib 0.11 (Debian 12) gives a handler no socket: under TLS it is the request's SSL's,
// else the process's socket with the request's two addresses. That one is found once (a walk of
// /proc/self/fd), then asked with one poll(2) as often as needed — at the hand-over too, inside the
// arbiter's judgement (hand_over.hpp), where a walk of every descriptor would hold a stop back.
// The socket stays open while its handler runs: httplib closes it after the handler returns.

namespace httplib {
struct Request;
}

namespace cellctl::web {

class ClientWatch {
 public:
  explicit ClientWatch(const httplib::Request& req);

  // The client closed its connection, or it cannot be found (then not obeyed either).
  [[nodiscard]] bool gone() const;

 private:
  int fd_ = -1;
};

}  // namespace cellctl::web
