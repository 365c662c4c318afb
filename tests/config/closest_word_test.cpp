// "Did you mean": the closest allowed word, a swap of two neighbours one step (issue 22: `cellctl reprot`).

#include "config/closest_word.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string_view>

namespace cellctl::config {
namespace {

constexpr std::array<std::string_view, 6> kCommands = {"run", "check", "home", "report", "compare", "serve"};

TEST(ClosestWord, ASwapOfNeighboursIsOneStep) {
  EXPECT_EQ(edit_distance("reprot", "report"), 1u);
  EXPECT_EQ(edit_distance("report", "report"), 0u);
  EXPECT_EQ(edit_distance("", "run"), 3u);
  EXPECT_EQ(edit_distance("hmoe", "home"), 1u);
}

TEST(ClosestWord, ATypoNamesItsCommand) {
  EXPECT_EQ(closest_word("reprot", kCommands), "report");
  EXPECT_EQ(closest_word("chek", kCommands), "check");
  EXPECT_EQ(closest_word("serv", kCommands), "serve");
}

TEST(ClosestWord, AnotherWordNamesNone) {
  EXPECT_EQ(closest_word("calibrate", kCommands), "");
}

}  // namespace
}  // namespace cellctl::config
