#pragma once
// The one interface the control loop drives every device session through (SCU, spindle converter,
// encoder over its DP master), and the one lifecycle they share:
//
//   each cycle:  receive(now)  — read what has arrived, complete or time out the request in flight,
//                                publish the snapshot in program units (mm, mm/s, Hz, typed flags);
//                ... monitor, supervisor, the runtime's commands to the session ...
//                transmit(now) — send what this cycle decided, so that a command decided in cycle k
//                                is on the wire in cycle k (the half-duplex line permitting: a request
//                                in flight is answered or timed out first), plus the device's own
//                                keep-alive and polls when due.
//
// lifecycle(): inactive → activating → active → deactivating → inactive; fault with fault_reason()
// from any state, left by activate() again. Neither receive() nor transmit() blocks or allocates (a
// fault reason is formatted into capacity reserved at construction).

#include <string>

#include "link/clock.hpp"
#include "link/fault_reason.hpp"
#include "link/lifecycle.hpp"
#include "link/link_health.hpp"

namespace cellctl::link {

class DeviceSession {
 public:
  virtual ~DeviceSession() = default;
  DeviceSession(const DeviceSession&) = delete;
  DeviceSession& operator=(const DeviceSession&) = delete;

  virtual void activate(TimePoint now) = 0;
  // Orderly shutdown (stop motion, leave remote mode …); lifecycle() says when it is done.
  virtual void deactivate(TimePoint now) = 0;
  virtual void receive(TimePoint now) = 0;
  virtual void transmit(TimePoint now) = 0;

  [[nodiscard]] Lifecycle lifecycle() const noexcept { return lifecycle_; }
  // Why the session is in Lifecycle::fault (empty otherwise).
  [[nodiscard]] const std::string& fault_reason() const noexcept { return fault_reason_; }
  [[nodiscard]] virtual const LinkHealth& health() const noexcept = 0;
  // A request is on the line or waiting for its reply: a command decided now goes out once it is
  // answered or timed out (the half-duplex line permitting). Always false for a bus master that
  // exchanges on its own schedule.
  [[nodiscard]] virtual bool awaiting_reply() const noexcept = 0;
  // Since the last good reply, or since activation while there was none.
  [[nodiscard]] Duration silent_for(TimePoint now) const noexcept {
    return health().silent_for(now, activated_at_);
  }
  // Inactive or faulted: nothing more will happen without activate().
  [[nodiscard]] bool quiet() const noexcept {
    return lifecycle_ == Lifecycle::inactive || lifecycle_ == Lifecycle::fault;
  }

 protected:
  DeviceSession() { fault_reason_.reserve(kFaultReasonCapacity); }

  // Entering any state but fault clears the reason.
  void enter(Lifecycle s, TimePoint now) noexcept {
    if (s == Lifecycle::activating) activated_at_ = now;
    enter(s);
  }
  void enter(Lifecycle s) noexcept {
    lifecycle_ = s;
    if (s != Lifecycle::fault) fault_reason_.clear();
  }
  template <class... Args>
  void enter_fault(fmt::format_string<Args...> format, Args&&... args) {
    lifecycle_ = Lifecycle::fault;
    assign_formatted(fault_reason_, format, std::forward<Args>(args)...);
  }

 private:
  Lifecycle lifecycle_ = Lifecycle::inactive;
  std::string fault_reason_;
  TimePoint activated_at_{};
};

}  // namespace cellctl::link
