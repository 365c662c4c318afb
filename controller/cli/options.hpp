#pragma once
// Options every cellctl command sees.

#include <string>

namespace cellctl::cli {

struct GlobalOptions {
  std::string config = "config/cell.yaml";
  std::string log_level = "info";
  bool trace = false;
};

}  // namespace cellctl::cli
