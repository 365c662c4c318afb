#pragma once
// Where the cycle's events go: the Journal in a run, a recording fake in tests.

#include "journal/event.hpp"

namespace cellctl::journal {

class EventSink {
 public:
  virtual ~EventSink() = default;
  // Cycle side: must not allocate, lock or do I/O.
  virtual void post(double t, const Payload& payload) noexcept = 0;
};

}  // namespace cellctl::journal
