#pragma once
// How a Teach-In step ended, in what its caller needs to write the result into the cell config (or
// to say why not): a part of runtime::RunResult for a Teach-In job.

#include <string>

#include "encoder/session.hpp"
#include "routines/teach_in.hpp"

namespace cellctl::runtime {

struct TeachInOutcome {
  bool done = false;  // taught and verified
  routines::TeachInResult result;
  std::string failure;
  bool restored = true;           // false: the encoder's configured parameters could not be confirmed
  encoder::SessionConfig taught;  // the settings to record (when done)
  double units_per_mm = 0.0;
};

}  // namespace cellctl::runtime
