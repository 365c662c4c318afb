#pragma once
// Which cellctl wrote a run record: `git describe --tags --always --dirty` taken when CMake
// configured the build (the project version when the source is not a git checkout). Only
// version.cpp is generated, so a new describe rebuilds one file.

#include <string_view>

namespace cellctl::journal {

[[nodiscard]] std::string_view cellctl_version() noexcept;

}  // namespace cellctl::journal
