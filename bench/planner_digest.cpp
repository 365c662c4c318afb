// Whether a change to the planner changes any plan: one line per plan of eleven seeded sets (3 and
// 6 DoF; from rest, moving, moving and accelerating targets, starts beyond the limits; time, none
// and phase synchronisation; with a travel limit around each axis's move), with its result, its
// duration and a hash of every axis's segments, end state, shortest duration and blocked intervals,
// all bit for bit. Build it at two commits and diff the outputs: a speed change that claims the
// same plans has none.
//
// Usage: planner_digest [--problems N (100000)] > digest.txt  (the accelerating targets and the
// starts beyond the limits take N / 4: the oracle's brake is slow to draw).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "planner/planner.hpp"
#include "planner/random_problems.hpp"

namespace {

using namespace cellctl::planner;

std::uint64_t mix(std::uint64_t h, double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return h ^ (bits + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
}

struct Set {
  const char* name;
  testing::Start start;
  testing::Target target;
  Synchronization sync;
  bool travel;  // each axis's travel 5 % (and 0.01) beyond its start and target: many are refused
};

template <int N>
void print_set(const Set& set, long count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Trajectory<N> trajectory;
  for (long c = 0; c < count; ++c) {
    std::vector<oracle::Problem> axes;
    for (int i = 0; i < N; ++i) axes.push_back(testing::random_problem(rng, set.start, set.target));
    Input<N> in = testing::input_of<N>(axes);
    in.synchronization = set.sync;
    for (int i = 0; i < N && set.travel; ++i) {
      const double lo = std::min(in.current_position[i], in.target_position[i]);
      const double hi = std::max(in.current_position[i], in.target_position[i]);
      in.min_position[i] = lo - 0.05 * (hi - lo) - 0.01;
      in.max_position[i] = hi + 0.05 * (hi - lo) + 0.01;
    }
    int axis = -1;
    const Result r = Trajectory<N>::calculate(in, trajectory, axis);
    std::uint64_t h = 0;
    for (int i = 0; i < N; ++i) {
      const JerkProfile& p = trajectory.profile(i);
      for (std::size_t k = 0; k < p.size(); ++k) h = mix(mix(h, p.segment(k).jerk), p.segment(k).duration);
      h = mix(mix(mix(h, p.end().position), p.end().velocity), p.end().acceleration);
      h = mix(h, trajectory.axis_min_duration(i));
      for (std::size_t b = 0; b < trajectory.blocked_count(i); ++b)
        h = mix(mix(h, trajectory.blocked(i, b).lo), trajectory.blocked(i, b).hi);
    }
    std::printf("%s %ld %d %a %d %016llx\n", set.name, c, static_cast<int>(r), trajectory.duration(), axis,
                static_cast<unsigned long long>(h));
  }
}

}  // namespace

int main(int argc, char** argv) {
  long problems = 100000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--problems" && i + 1 < argc) {
      problems = std::strtol(argv[++i], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: planner_digest [--problems N]\n");
      return 2;
    }
  }
  using S = testing::Start;
  using T = testing::Target;
  const long quarter = std::max(1L, problems / 4);
  print_set<3>({"3rest", S::at_rest, T::at_rest, Synchronization::time, false}, problems, 1);
  print_set<3>({"3moving", S::moving, T::at_rest, Synchronization::time, false}, problems, 2);
  print_set<6>({"6moving", S::moving, T::at_rest, Synchronization::time, false}, problems, 3);
  print_set<3>({"3moving_target", S::moving, T::moving, Synchronization::time, false}, problems, 4);
  print_set<3>({"3accelerating", S::moving, T::accelerating, Synchronization::time, false}, quarter, 5);
  print_set<3>({"3beyond", S::beyond_limits, T::at_rest, Synchronization::time, false}, quarter, 6);
  print_set<3>({"3none", S::moving, T::at_rest, Synchronization::none, false}, problems, 7);
  print_set<3>({"3phase", S::moving, T::at_rest, Synchronization::phase, false}, problems, 8);
  print_set<3>({"3travel", S::moving, T::at_rest, Synchronization::time, true}, problems, 9);
  print_set<3>({"3travel_moving_target", S::moving, T::moving, Synchronization::time, true}, problems, 10);
  print_set<3>({"3travel_phase", S::moving, T::at_rest, Synchronization::phase, true}, problems, 11);
  return 0;
}
