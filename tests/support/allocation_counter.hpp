#pragma once
// Counts heap allocations made through the global operator new, so that tests and benchmarks can
// prove a cyclic path allocates nothing. Link allocation_counter.cpp (which replaces the global
// operator new) into the executable that uses it.

#include <cstddef>

namespace cellctl::testing {

// Allocations since the program started, on every thread.
[[nodiscard]] std::size_t allocation_count() noexcept;
// Allocations made by the calling thread only (a cycle's count without its helper threads').
[[nodiscard]] std::size_t thread_allocation_count() noexcept;

}  // namespace cellctl::testing
