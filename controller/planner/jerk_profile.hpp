#pragma once
// A one-dimensional motion made of constant-jerk segments from a known start state. Every profile
// the planner builds (a brake, a time-optimal profile, a profile stretched to a common duration)
// is stored in this one form, so one evaluation function integrates them all and there is a single
// place where the physics lives. Fixed-size storage: building and evaluating never allocate.

#include <array>
#include <cassert>
#include <cstddef>
#include <cstring>

namespace cellctl::planner {

// A plain aggregate (MotionState{} is zero; no default member values): an axis's planning state
// is then not zeroed for every axis planned before plan() sets it.
struct MotionState {
  double position;
  double velocity;
  double acceleration;
};

// A plain aggregate (JerkSegment{} is zero; no default member values): a profile's unused segment
// slots are then left unwritten, which saved zeroing 256 bytes per profile and plan.
struct JerkSegment {
  double jerk;
  double duration;
};

// The state reached from `s` after `t` seconds at constant jerk `jerk`. Inline (as append() is):
// building a profile chains these, and out of line each state went through memory.
[[nodiscard]] inline MotionState integrate(const MotionState& s, double jerk, double t) noexcept {
  return MotionState{
      s.position + t * (s.velocity + t * (s.acceleration / 2.0 + t * jerk * (1.0 / 6.0))),
      s.velocity + t * (s.acceleration + t * jerk / 2.0),
      s.acceleration + t * jerk,
  };
}

// Where a position extremum of a profile is, and when.
struct PositionExtremum {
  double position = 0.0;
  double time = 0.0;
};

struct PositionExtrema {
  PositionExtremum min;
  PositionExtremum max;
};

class JerkProfile {
 public:
  // The longest profile: a mix (travel_fit.hpp) of a blend — a brake (3 segments) and 13 (two
  // 7-segment extreme profiles, their switching times merged) — and a turn (2), a brake and 13, held
  // at the target (1): their switching times merged, at most 35.
  static constexpr std::size_t kMaxSegments = 40;

  JerkProfile() = default;
  explicit JerkProfile(const MotionState& start) noexcept : start_(start), end_(start) {}
  // Copies only the segments in use: planning copies profiles (an axis's brake into each profile
  // built from it; with a travel or phase synchronisation the scratch trajectory into the caller's),
  // and a whole copy cost more than building them.
  JerkProfile(const JerkProfile& other) noexcept { *this = other; }
  JerkProfile& operator=(const JerkProfile& other) noexcept {
    start_ = other.start_;
    end_ = other.end_;
    count_ = other.count_;
    duration_ = other.duration_;
    for (std::size_t i = 0; i < count_; ++i) segments_[i] = other.segments_[i];
    return *this;
  }
  ~JerkProfile() = default;

  // Where segments take a motion: its end state and the time then.
  struct Reached {
    MotionState end;
    double time;
  };
  // Segments made before the profile they go to is touched (its caller checks where they lead
  // first): counts `segment` among the first n of `kept` unless it is empty, and moves `r` on by it
  // as append() does (the state kept in registers); assign_kept() then copies them in at once. No
  // branch on whether it is empty (in a profile's pieces that is data): it is written in slot n
  // either way and integrated over max(duration, 0), which for an empty one changes nothing but a
  // position of -0.0 into +0.0. Precondition: room for one more slot after the n kept.
  static void keep(JerkSegment* kept, std::size_t& n, Reached& r, JerkSegment segment) noexcept {
    const double duration = segment.duration > 0.0 ? segment.duration : 0.0;
    keep_timed(kept, n, r.time, segment);
    r.end = integrate(r.end, segment.jerk, duration);
  }
  // keep() without the integration, `time` moved on: for pieces whose end state the caller knows
  // otherwise (AxisProfile::prepare).
  static void keep_timed(JerkSegment* kept, std::size_t& n, double& time, JerkSegment segment) noexcept {
    const bool counted = segment.duration > 0.0;
    const double duration = counted ? segment.duration : 0.0;
    kept[n] = {segment.jerk, duration};
    n += counted ? 1U : 0U;
    time += duration;
  }

  // Adds segments after the last one; zero-length segments are dropped. Precondition: they fit in
  // kMaxSegments (the shapes are built by code that knows their length). Several at once keep the
  // state in registers: one at a time it went through memory, a stall per segment.
  void append(const JerkSegment* segments, std::size_t n) noexcept {
    // One loop, not an integration pass and then the stores: two loops cost 2 % of a moving plan.
    MotionState end = end_;
    double duration = duration_;
    std::size_t count = count_;
    for (std::size_t i = 0; i < n; ++i) {
      const JerkSegment& segment = segments[i];
      if (!(segment.duration > 0.0)) continue;
      assert(count < kMaxSegments);
      segments_[count++] = segment;
      end = integrate(end, segment.jerk, segment.duration);
      duration += segment.duration;
    }
    end_ = end;
    duration_ = duration;
    count_ = count;
  }
  void append(JerkSegment segment) noexcept { append(&segment, 1); }
  // Becomes `head` followed by the first n of `segments`, kept by keep() from head's end, which
  // took it to `r` (head's end, duration and count are not copied first). All M slots copied at
  // once (a fixed-size copy; a loop over them, each tested for its duration, cost as much as
  // building them), the first n kept. Precondition: head.size() + M <= kMaxSegments.
  template <std::size_t M>
  void assign_kept(const JerkProfile& head, const std::array<JerkSegment, M>& segments, std::size_t n,
                   const Reached& r) noexcept {
    assert(head.count_ + M <= kMaxSegments && n <= M);
    start_ = head.start_;
    for (std::size_t i = 0; i < head.count_; ++i) segments_[i] = head.segments_[i];
    std::memcpy(&segments_[head.count_], segments.data(), sizeof(segments));
    end_ = r.end;
    duration_ = r.time;
    count_ = head.count_ + n;
  }

  [[nodiscard]] const MotionState& start() const noexcept { return start_; }
  [[nodiscard]] const MotionState& end() const noexcept { return end_; }
  [[nodiscard]] double duration() const noexcept { return duration_; }
  [[nodiscard]] std::size_t size() const noexcept { return count_; }
  [[nodiscard]] const JerkSegment& segment(std::size_t i) const noexcept { return segments_[i]; }

  // The state at time t since the start; before 0 the start state, after duration() the end state
  // (the target state, which the planner holds).
  [[nodiscard]] MotionState at(double t) const noexcept;
  // The jerk at time t (0 outside the profile).
  [[nodiscard]] double jerk_at(double t) const noexcept;
  // The lowest and highest position over the whole profile, with their times (overshoot included).
  [[nodiscard]] PositionExtrema extrema() const noexcept;

 private:
  MotionState start_{};
  MotionState end_{};
  std::array<JerkSegment, kMaxSegments> segments_;  // the first count_ are set (see JerkSegment)
  std::size_t count_ = 0;
  double duration_ = 0.0;
};

}  // namespace cellctl::planner
