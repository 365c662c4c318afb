// Issue 22 item 8: a confirmation takes yes in any case; everything else, and no answer, is no.

#include "cli/confirm.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace cellctl::cli {
namespace {

TEST(Confirm, YesInAnyCaseConfirms) {
  for (const char* yes : {"yes", "Yes", "YES", "yEs", "y", "Y", " yes ", "Yes\r"})
    EXPECT_TRUE(is_yes(yes)) << yes;
}

TEST(Confirm, AnythingElseDoesNot) {
  for (const char* no : {"", " ", "no", "n", "N", "ye", "yess", "yes please", "ja", "1", "true"})
    EXPECT_FALSE(is_yes(no)) << no;
}

TEST(Confirm, AskReadsOneLine) {
  std::istringstream typed("Yes\nno\n");
  EXPECT_TRUE(ask_yes("Move?", typed));
  EXPECT_FALSE(ask_yes("Move?", typed));
  EXPECT_FALSE(ask_yes("Move?", typed)) << "the end of input is no";
}

TEST(Confirm, AssumedByYesWithoutAsking) {
  EXPECT_EQ(confirm("Move?", true), Confirmation::confirmed);
}

}  // namespace
}  // namespace cellctl::cli
