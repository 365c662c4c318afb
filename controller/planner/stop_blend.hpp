#pragma once
// The profile of an axis to a target at rest at a duration longer than its shortest: the extreme
// profile on the target's side blended with the fastest stop held at rest (why that is valid, how
// the share is found and where the blend ends: AxisProfile::prepare). Inline: prepare() keeps the
// time it sums in a register.

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "planner/farthest_profile.hpp"
#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// The blend's pieces: `extreme_jerk` times the extreme's jerk signs over its durations `d`, plus
// `stop_jerk` times the stop's (+1, 0, -1 over its ramps and hold, then 0 at rest until the
// extreme ends), kept after the first n of `pieces` (empty ones dropped), `time` moved on by them.
// Not integrated: the dynamics are linear in the jerk, so the blend ends in the same blend of the
// extreme's and the stop's end states (at rest, at the blend of their positions, which prepare()
// checks; integrating the ten pieces again was 11 % of a moving plan's instructions).
//
// The two switching sequences are merged in time order, one switch per step: 7 of the extreme's
// and 3 of the stop's, 10 steps. Where two switches coincide a step makes an empty piece: stored and
// timed (which changes nothing) but not counted, as in JerkProfile::keep(). Which switch comes next
// is data, and the steps form one chain: each sequence's next switch is carried in a register and
// the one after it loaded ahead, so that a step does not wait on a load from the index the step
// before computed (about ten cycles a step: carried, the plans took 0.95-0.965 of the time). The
// times are compared as integers (see below); g++ makes each step a three-way branch on them (the
// extreme's switch first, the stop's, or both), which the processor predicts well on the bench's
// moves: 0.97-0.99 of the time of the steps made branch-free (selections by masks on the doubles;
// by masks on the integers 1.015 of that), though callgrind's simple branch model counts 5.9
// mispredictions per axis against 4.4.
template <std::size_t M>
[[gnu::always_inline]] inline void blend_with_stop(const SevenDurations& d, double extreme_jerk,
                                                   const Reach& stop, double stop_jerk,
                                                   std::array<JerkSegment, M>& pieces, std::size_t& n,
                                                   double& time) noexcept {
  constexpr std::size_t kSteps = kFarthestJerkSigns.size() + 3;
  static_assert(M >= kSteps, "room for every piece of the blend");
  const std::array<double, 4> stop_jerks{stop_jerk, 0.0, -stop_jerk, 0.0};
  // Switch times are compared and selected as their bit patterns, in integer registers: for times
  // >= 0 their order as signed integers is their order as doubles (a ramp of -0.0 orders before
  // +0.0, but switches at one time only make an empty piece between them, in either order).
  using Bits = std::int64_t;
  const auto bits = [](double x) { return std::bit_cast<Bits>(x); };
  const double stop_peak = stop.ramp_in + stop.hold;
  const Bits never = bits(std::numeric_limits<double>::infinity());
  // The stop's switches, then never (read one ahead: see below).
  const std::array<Bits, 5> stop_ends{bits(stop.ramp_in), bits(stop_peak), bits(stop_peak + stop.ramp_out),
                                      never, never};
  // The extreme's switches, then its end repeated: after k steps its index is at most k, so these
  // hold every one read (one ahead included).
  std::array<Bits, kSteps + 2> extreme_ends;
  std::array<double, kSteps> extreme_jerks;
  double sum = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    sum += d[i];
    extreme_ends[i] = bits(sum);
    extreme_jerks[i] = extreme_jerk * kFarthestJerkSigns[i];
  }
  for (std::size_t i = d.size(); i < kSteps; ++i) {
    extreme_ends[i] = bits(sum);
    extreme_jerks[i] = 0.0;
  }
  extreme_ends[kSteps] = bits(sum);
  extreme_ends[kSteps + 1] = bits(sum);
  std::size_t ie = 0;
  std::size_t is = 0;
  Bits e = extreme_ends[0];
  Bits e_after = extreme_ends[1];
  Bits s = stop_ends[0];
  Bits s_after = stop_ends[1];
  double from = 0.0;
  for (std::size_t k = 0; k < kSteps; ++k) {
    // Which switch comes next, from the two switches themselves (both at a tie).
    const bool take_e = e <= s;
    const bool take_s = s <= e;
    const double to = std::bit_cast<double>(take_e ? e : s);
    const double piece = to - from;
    const double jerk = extreme_jerks[ie] + stop_jerks[is];
    pieces[n] = {jerk, piece};
    n += piece > 0.0 ? 1U : 0U;
    time += piece;
    ie += take_e ? 1U : 0U;
    is += take_s ? 1U : 0U;
    e = take_e ? e_after : e;
    s = take_s ? s_after : s;
    e_after = extreme_ends[ie + 1];
    s_after = stop_ends[is + 1];
    from = to;
  }
}

}  // namespace cellctl::planner
