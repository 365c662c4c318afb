#pragma once
// The safe-stop at the end of a run: every device is brought to rest and stays watched until its rest
// is confirmed by the device (observed) or a stated bound has passed after which the device's own
// protection has surely acted (bounded); what is neither is unknown and said loudly. The loop keeps
// cycling (receive … transmit) until every device is resolved, so cellctl never exits before.
//
//  - SCU: stopped and closed in order (RS, RA). A session that lost its SCU (port gone, silence,
//    garbage) is given its port again (CellLinks::reopen) and activated again every `retry`; once it
//    is back, F20 stops every actuator and a refresh after the F20 shows whether they are at rest
//    (observed). Attempts end at the first bound: the SCU's communication time-out (0.5 s after the
//    last request that may have reached it, whatever the Safety_ID: every motion of ours is remote)
//    plus the actuators' stopping time (scu.stopping_time_ms); rest is bounded once the last request
//    sent is that long ago. The encoder keeps being read meanwhile and its last position is recorded.
//  - Spindle: CMD System Stopp, sent again (port reopened, session activated again) until the
//    converter reports STILLSTAND (observed). The converter has no communication watchdog (its manual
//    names none): without an answer within `confirm_within` of the end it is unknown — it may still
//    turn at the last set frequency. Never started since it was last seen at rest: bounded.
//  - Encoder: it moves nothing of its own; observed while its positions could be watched to the end,
//    bounded (nothing to stop) when its link was lost. It is closed after the SCU is resolved.
//
// observe() every cycle of the run and step() every cycle from begin() on allocate nothing; the
// verdicts' words are composed after the loop.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "cell/cell_state.hpp"
#include "config/cell_config.hpp"
#include "link/clock.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/cell_links.hpp"

namespace cellctl::runtime {

enum class Safe : std::uint8_t { observed, bounded, unknown };
[[nodiscard]] constexpr const char* to_string(Safe s) noexcept {
  return s == Safe::observed ? "observed" : s == Safe::bounded ? "bounded" : "unknown";
}

struct DeviceSafety {
  Safe safe = Safe::unknown;
  std::string evidence;
};

class SafeStop {
 public:
  static constexpr link::Duration kScuCommunicationTimeout = std::chrono::milliseconds(500);
  static constexpr link::Duration kRetry = std::chrono::milliseconds(100);

  // `confirm_within`: how long after begin() a stop is sent again for a device without a bound of its
  // own (the spindle). `start`: the run's start, for the times in the evidence.
  SafeStop(const config::CellConfig& cell, CellDevices& devices, CellLinks& links,
           link::Duration confirm_within, link::TimePoint start);

  // Every cycle of the run, after the sessions' receive(): what the devices last said.
  void observe(link::TimePoint now) noexcept;
  // The run is over: the orderly shutdown begins (the encoder is kept to watch the axes).
  void begin(link::TimePoint now);
  [[nodiscard]] bool begun() const noexcept { return begun_at_.has_value(); }
  // Every cycle, before the sessions' transmit(). `stopping`: the monitor demands a stop of category
  // 0 or 1 — a device lost meanwhile is recovered and stopped at once, not only once the run is over
  // (under a category-2 hold nothing is recovered: the hold keeps the spindle turning on purpose).
  // From begin() on every device is brought to rest.
  void step(link::TimePoint now, bool stopping);
  // Every device present is resolved.
  [[nodiscard]] bool done() const noexcept;

  // When a device's session lost it (since its last good reply, in s from the start) and why.
  [[nodiscard]] std::optional<double> lost_at_s(cell::Device d) const noexcept {
    const auto& t = track_[static_cast<std::size_t>(d)];
    return t.lost_at ? std::optional(t_of(*t.lost_at)) : std::nullopt;
  }
  [[nodiscard]] const std::string& lost_reason(cell::Device d) const noexcept {
    return track_[static_cast<std::size_t>(d)].lost_reason;
  }

  // After the loop: per device (nullopt for a device the cell lacks).
  [[nodiscard]] std::array<std::optional<DeviceSafety>, cell::kDevices> verdicts() const;

 private:
  struct Track {
    bool present = false;
    std::optional<Safe> resolved;
    link::TimePoint resolved_at{};
    std::optional<link::TimePoint> lost_at;  // first seen in fault
    std::string lost_reason;                 // the session's fault reason then (reserved capacity)
    link::TimePoint next_retry{};
    int reopen_failures = 0;
    int recoveries = 0;  // activations after a loss
  };
  struct ScuWatch {
    link::TimePoint bound_at{};              // communication time-out + stopping time after last_sent
    std::optional<link::TimePoint> give_up;  // no attempt after the first bound
    bool f20_asked = false;
    std::optional<std::uint64_t> refreshes_at_f20;
    std::optional<link::TimePoint> rest_seen_at;  // a refresh after the stop showed every actuator at rest
    std::optional<link::TimePoint> closed_at;     // RA answered
    bool moving_at_close = false;
    std::array<double, cell::kMaxAxes> last_mm{};
    std::optional<link::TimePoint> last_refresh;
  };
  struct SpindleWatch {
    double last_set_hz = 0.0;  // the last frequency a start or a change asked for
    bool run_sent = false;     // a start went out since the converter was last seen at rest
    std::optional<link::TimePoint> last_status;
    bool last_at_rest = true;
    std::optional<link::TimePoint> standstill_at;
  };
  struct EncoderWatch {
    std::optional<link::TimePoint> last_seen;  // in data exchange
    bool missed = false;  // out of data exchange in a cycle after the end: not watched to the end
    double mm = 0.0;
    double mm_s = 0.0;
  };

  void step_scu(link::TimePoint now);
  void step_spindle(link::TimePoint now);
  void step_encoder(link::TimePoint now);
  // Reopens the port and activates the session again, every kRetry.
  void recover(cell::Device d, link::DeviceSession& s, link::TimePoint now);
  void note_loss(Track& t, const link::DeviceSession& s, link::TimePoint now);
  void resolve(Track& t, Safe safe, link::TimePoint now) noexcept;
  [[nodiscard]] double t_of(link::TimePoint p) const noexcept { return link::to_seconds(p - start_); }
  [[nodiscard]] std::string scu_evidence() const;
  [[nodiscard]] std::string spindle_evidence() const;
  [[nodiscard]] std::string encoder_evidence() const;

  const config::CellConfig& cell_;
  CellDevices& devices_;
  CellLinks& links_;
  link::Duration confirm_within_;
  link::TimePoint start_;
  std::optional<link::TimePoint> begun_at_;
  std::array<Track, cell::kDevices> track_{};
  ScuWatch scu_;
  SpindleWatch spindle_;
  EncoderWatch encoder_;
};

}  // namespace cellctl::runtime
