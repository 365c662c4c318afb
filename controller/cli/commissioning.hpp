#pragma once
// What every commissioning command (scu, spindle, encoder) does with its device's session, written
// once: open the port (cli::DeviceLink), step the session through the interface every session offers
// (link::DeviceSession: receive, then transmit) on the real clock until a condition holds, and report
// a failure the same way — the session's fault reason (exit 4), Ctrl-C (130) or a time-out.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <string>

#include "cli/device_group.hpp"
#include "cli/device_link.hpp"
#include "cli/drive.hpp"
#include "cli/options.hpp"
#include "cli/terminal_screen.hpp"
#include "config/line_section.hpp"
#include "exit_codes/exit_codes.hpp"
#include "link/clock.hpp"
#include "link/device_session.hpp"

namespace cellctl::cli {

template <class Session>
class Commissioning {
 public:
  static constexpr link::Duration kProgressEvery = std::chrono::milliseconds(500);

  // Throws link::LinkError when the port cannot be opened, std::invalid_argument for a bad config.
  template <class SessionConfig>
  Commissioning(const GlobalOptions& global, const DeviceOptions& options, const config::PortConfig& port,
                const char* device, const SessionConfig& config)
      : options_(options),
        device_(device),
        link_(port, options.port, device, clock_, global.trace),
        session_(link_.link(), config) {}

  [[nodiscard]] Session& session() noexcept { return session_; }
  [[nodiscard]] const auto& snapshot() const noexcept { return session_.snapshot(); }
  [[nodiscard]] const link::Clock& clock() const noexcept { return clock_; }
  [[nodiscard]] const std::string& path() const noexcept { return link_.path(); }
  [[nodiscard]] bool faulted() const noexcept { return session_.lifecycle() == link::Lifecycle::fault; }

  void activate() { session_.activate(clock_.now()); }
  void step(link::TimePoint now) {
    session_.receive(now);
    session_.transmit(now);
  }
  // Steps the session until done() holds: false on a fault, a time-out (the --timeout unless given)
  // or Ctrl-C/SIGTERM.
  template <class Done>
  bool drive(Done&& done, link::Duration timeout = link::Duration::zero()) {
    if (timeout == link::Duration::zero()) timeout = options_.timeout();
    return drive_until(
               clock_, timeout, [&](auto now) { step(now); }, [&] { return faulted() || done(); }) &&
           !faulted();
  }
  // drive() that shows how the work goes, so a command is never silent while it waits: a line from
  // `progress()` at once and then every 0.5 s, with the time since — on a terminal one status line
  // rewritten in place (the last one kept), piped (a log) a line each.
  template <class Done, class Progress>
  bool drive_showing(Done&& done, Progress&& progress) {
    TerminalScreen screen;
    const auto started = clock_.now();
    auto next = started;
    return drive([&] {
      if (const auto now = clock_.now(); now >= next) {
        screen.status(fmt::format("{:5.1f} s  {}", link::to_seconds(now - started), progress()));
        next = now + kProgressEvery;
      }
      return done();
    });
  }
  bool drive_for(link::Duration span) {
    const auto until = clock_.now() + span;
    return drive([&] { return clock_.now() >= until; });
  }
  // Deactivates and drives until the session is inactive (also after Ctrl-C, which is cleared for
  // it and reported by the return value: true when it had been pressed).
  bool shut_down(bool& closed) {
    const bool interrupted = g_interrupted.exchange(false);
    session_.deactivate(clock_.now());
    closed = drive([&] { return session_.lifecycle() == link::Lifecycle::inactive; });
    return interrupted;
  }

  // The session's own state stands in the way (not active, queue full, parameters), not the command line.
  int refuse(const char* what) const {
    spdlog::error("the {} session would not {}", device_, what);
    return kExitFailed;
  }
  // After drive() returned false: the fault with its reason (kExitLink), Ctrl-C, or a time-out
  // (`timed_out`).
  int failed_to(const char* what, int timed_out = kExitFailed) const {
    if (g_interrupted.load()) return kExitInterrupted;
    if (faulted()) {
      // Most reasons name the device and its link already ("SCU on P (38400 8N1): …"): said once.
      const auto& reason = session_.fault_reason();
      if (reason.find(path()) != std::string::npos)
        spdlog::error("{}", reason);
      else
        spdlog::error("{} on {}: {}", device_, path(), reason);
      return kExitLink;
    }
    spdlog::error("{} on {} did not {} within {} s", device_, path(), what, options_.timeout_s);
    return timed_out;
  }

 private:
  const DeviceOptions& options_;
  const char* device_;
  link::MonotonicClock clock_;
  DeviceLink link_;
  Session session_;
};

}  // namespace cellctl::cli
