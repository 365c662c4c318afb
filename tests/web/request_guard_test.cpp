// The page's guard on requests built by hand (no server): Host and Origin, the token and the session,
// the back-off of wrong tokens (its windows, on an injected clock), sessions' end.
#include "web/request_guard.hpp"

#include <gtest/gtest.h>
#include <httplib.h>

#include <string>
#include <variant>

#include "web/failure_backoff.hpp"
#include "web/session_store.hpp"

namespace cellctl::web {
namespace {

using namespace std::chrono_literals;

constexpr const char* kToken = "request-guard-token-0123";

PageOptions options() {
  PageOptions o;
  o.port = 8443;
  o.token = kToken;
  o.allowed_hosts = {"cell7.plant.example"};
  return o;
}

httplib::Request request(std::string method, std::string path, std::string host = "10.0.0.5:8443") {
  httplib::Request r;
  r.method = std::move(method);
  r.path = std::move(path);
  r.local_addr = "10.0.0.5";
  r.local_port = 8443;
  r.remote_addr = "10.0.0.9";
  r.remote_port = 50000;
  r.set_header("Host", host);
  return r;
}

TEST(RequestGuard, HostMustNameTheAddressReachedOrAnAllowedNameWithThePagesPort) {
  RequestGuard guard(options());
  EXPECT_EQ(guard.admit(request("GET", "/")).status, 0);
  EXPECT_EQ(guard.admit(request("GET", "/", "CELL7.plant.example:8443")).status, 0);
  EXPECT_EQ(guard.admit(request("GET", "/", "evil.example:8443")).status, 403);
  EXPECT_EQ(guard.admit(request("GET", "/", "10.0.0.5:8080")).status, 403);
  EXPECT_EQ(guard.admit(request("GET", "/", "10.0.0.5")).status, 403);        // port 80 implied
  EXPECT_EQ(guard.admit(request("GET", "/", "localhost:8443")).status, 403);  // not reached on loopback
  EXPECT_EQ(guard.admit(request("GET", "/", "")).status, 403);
  auto foreign = request("GET", "/");
  foreign.set_header("Origin", "http://evil.example");
  EXPECT_EQ(guard.admit(foreign).status, 403);
  auto own = request("GET", "/");
  own.set_header("Origin", "http://10.0.0.5:8443");
  EXPECT_EQ(guard.admit(own).status, 0);
  EXPECT_EQ(guard.counters().forbidden, 6u);
}

TEST(RequestGuard, TokenOrSessionBeforeTheBodysSize) {
  RequestGuard guard(options());
  auto big = request("POST", "/cmd/stop");
  big.set_header("Content-Length", "200000000");
  EXPECT_EQ(guard.admit(big).status, 401);  // who asks first: nothing else is told
  big.set_header("X-Cellctl-Token", kToken);
  EXPECT_EQ(guard.admit(big).status, 413);
  auto no_length = request("POST", "/cmd/stop");
  no_length.set_header("Authorization", std::string("Bearer ") + kToken);
  EXPECT_EQ(guard.admit(no_length).status, 411);
  auto get_with_body = request("GET", "/events");
  get_with_body.set_header("Transfer-Encoding", "chunked");
  EXPECT_EQ(guard.admit(get_with_body).status, 400);
  EXPECT_EQ(guard.admit(request("PUT", "/cmd/stop")).status, 405);
}

TEST(RequestGuard, ACommandWithAWrongTokenOfTheRightLengthIsRefused) {
  RequestGuard guard(options());
  std::string wrong = kToken;
  wrong.back() = wrong.back() == '4' ? '5' : '4';  // one byte off: the comparison must read every byte
  for (const auto* header : {"X-Cellctl-Token", "Authorization"}) {
    auto stop = request("POST", "/cmd/stop");
    stop.set_header("Content-Length", "2");
    stop.set_header(header, std::string(header[0] == 'A' ? "Bearer " : "") + wrong);
    EXPECT_EQ(guard.admit(stop).status, 401) << header;
    EXPECT_FALSE(guard.caller(stop)) << header;
  }
  EXPECT_EQ(guard.counters().wrong_tokens, 2u);
  auto right = request("POST", "/cmd/stop");
  right.set_header("Content-Length", "2");
  right.set_header("X-Cellctl-Token", kToken);
  EXPECT_EQ(guard.admit(right).status, 0);
}

TEST(RequestGuard, LoginGivesASessionThatCommandsAndEventsAcceptUntilLogout) {
  RequestGuard guard(options());
  auto login = request("POST", "/login");
  login.set_header("X-Cellctl-Token", kToken);
  const auto result = guard.login(login);
  ASSERT_TRUE(std::holds_alternative<SessionStore::Opened>(result));
  const auto& session = std::get<SessionStore::Opened>(result);
  EXPECT_EQ(session.id.size(), 32u);
  const auto cookie = guard.session_cookie(session.id);
  EXPECT_NE(cookie.find("HttpOnly"), std::string::npos);
  EXPECT_NE(cookie.find("SameSite=Strict"), std::string::npos);
  auto events = request("GET", "/events");
  events.set_header("Cookie", "other=1; cellctl_session=" + session.id);
  EXPECT_EQ(guard.admit(events).status, 0);
  ASSERT_TRUE(guard.caller(events));
  EXPECT_EQ(guard.caller(events)->who, "session #1");
  guard.logout(events);
  EXPECT_EQ(guard.admit(events).status, 401);
}

TEST(FailureBackoff, FiveFreeThenAWindowThatDoubles) {
  FailureBackoff backoff;
  const auto t0 = FailureBackoff::Clock::time_point{} + 1h;
  for (unsigned i = 0; i + 1 < FailureBackoff::kFreeFailures; ++i) backoff.failed("a", t0);
  EXPECT_EQ(backoff.blocked("a", t0).count(), 0);
  backoff.failed("a", t0);
  EXPECT_EQ(backoff.blocked("a", t0).count(), 1);
  EXPECT_EQ(backoff.blocked("b", t0).count(), 0);  // per address
  backoff.failed("a", t0 + 1s);
  EXPECT_EQ(backoff.blocked("a", t0 + 1s).count(), 2);
  for (int i = 0; i < 20; ++i) backoff.failed("a", t0 + 2s);
  EXPECT_EQ(backoff.blocked("a", t0 + 2s).count(), 256);  // capped
  backoff.succeeded("a");
  EXPECT_EQ(backoff.blocked("a", t0 + 2s).count(), 0);
}

TEST(SessionStore, ExpiresAndKeepsAtMostItsCapacity) {
  SessionStore store(10s, 2);
  const auto t0 = SessionStore::Clock::time_point{} + 1h;
  const auto a = store.open(t0);
  const auto b = store.open(t0);
  EXPECT_NE(a.id, b.id);
  EXPECT_EQ(store.find(a.id, t0), a.number);
  const auto c = store.open(t0);  // the oldest goes
  EXPECT_FALSE(store.find(a.id, t0));
  EXPECT_EQ(store.find(c.id, t0 + 9s), c.number);
  EXPECT_FALSE(store.find(c.id, t0 + 10s));
  EXPECT_FALSE(store.open_now(b.number, t0 + 10s));
}

}  // namespace
}  // namespace cellctl::web
