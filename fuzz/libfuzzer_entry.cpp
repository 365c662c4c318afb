// libFuzzer's entry point for one target; CMake compiles this file once per target, naming the
// target's function in CELLCTL_FUZZ_TARGET.

#include <cstddef>
#include <cstdint>
#include <span>

#include "targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  CELLCTL_FUZZ_TARGET(std::span<const std::uint8_t>(data, size));
  return 0;
}
