#pragma once
// Expects `fn` to throw a config::ConfigError whose message is exactly `message`: the one check of
// every "file:line:column: field: rule" message in the config and recipe tests.

#include <gtest/gtest.h>

#include <string>

#include "config/yaml_node.hpp"

namespace cellctl::testing {

template <class Fn>
void expect_config_error(Fn&& fn, const std::string& message) {
  try {
    fn();
    ADD_FAILURE() << "expected: " << message;
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

}  // namespace cellctl::testing
