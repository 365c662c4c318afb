#pragma once
// The shortest duration from rest to rest over a distance, in closed form: the common case (every
// recipe move from a standstill) needs no root search. Accelerating uses the limits of the
// direction of travel, braking the opposite acceleration bound (max_acceleration/min_acceleration
// may differ).

#include <array>
#include <cstddef>

#include "planner/axis_limits.hpp"
#include "planner/farthest_profile.hpp"
#include "planner/jerk_profile.hpp"

namespace cellctl::planner {

// distance: signed; limits: finite and of the right signs. Returns 0 for a zero distance.
[[nodiscard]] double rest_to_rest_time(double distance, const AxisLimits& limits) noexcept;

// The farthest profile of duration T from rest to rest with symmetric limits (FarthestProfile's,
// in closed form, with its seven durations in `t`): accelerating as hard as it may for T / 2 and
// braking as a mirror image, cruising at max_velocity in between once T allows it. Its position:
// the peak velocity times T / 2 (each half's velocity is point-symmetric about its middle), plus
// the cruise. Why: every recipe move is one, and FarthestProfile's general set-up and case search
// were most of its plan.
[[nodiscard]] double rest_to_rest_farthest(double T, const AxisLimits& limits, SevenDurations& t) noexcept;

// The profile from rest to rest over `distance` (signed) of duration T, with symmetric limits: where
// T is the shortest duration (`shortest`) and the farthest profile on the distance's side gets there
// to rounding, that profile; otherwise the blend of the farthest and the nearest profile (the
// farthest mirrored: the farthest profile scaled) that ends on the distance. Its 7 pieces (some may
// be empty); false when T has no profile (below the shortest duration).
[[nodiscard]] bool rest_to_rest_pieces(double T, bool shortest, double distance, const AxisLimits& limits,
                                       std::array<JerkSegment, kFarthestJerkSigns.size()>& pieces) noexcept;

}  // namespace cellctl::planner
