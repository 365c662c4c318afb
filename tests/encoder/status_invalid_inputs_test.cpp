// Issue 22 item 8: `cellctl encoder status` against a slave whose every input is `ff ff ff ff` (a Class 2
// word with bit 31 set, which the manual says is always 0) said "bus active (data_exchange), 11
// exchanges, last input 41.4 ms ago, position 0 counts" and exited 0. Its text and verdict
// (cli/encoder_status) from the session against the emulator made to send all ones: invalid, said so,
// no position, no "last input" that was never valid; and true again once the inputs are.
#include <gtest/gtest.h>

#include "cli/encoder_status.hpp"
#include "session_rig.hpp"

namespace cellctl::encoder {
namespace {

using namespace std::chrono_literals;
using testing::Rig;

TEST(EncoderStatus, InputsAllOnesAreReportedInvalidWithoutAPositionOrALastInput) {
  Rig rig(Functionality::class2);
  rig.move_to(10.0);
  rig.emulator->set_inputs_all_ones(true);
  Session& session = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << session.fault_reason();
  rig.run_for(20ms);
  const Snapshot& s = session.snapshot();

  EXPECT_FALSE(cli::encoder_inputs_valid(s)) << "status must not exit 0";
  const auto text = cli::encoder_input_lines(session.lifecycle(), s);
  EXPECT_NE(text.find(fmt::format("{} inputs INVALID", s.bad_inputs)), std::string::npos) << text;
  EXPECT_NE(text.find("no valid input in the "), std::string::npos) << text;
  EXPECT_EQ(text.find("last valid input"), std::string::npos) << text;
  EXPECT_NE(text.find("position       INVALID: bit 31 set"), std::string::npos) << text;
  EXPECT_EQ(text.find("counts ="), std::string::npos) << "no position shown from an invalid input: " << text;
  EXPECT_GE(s.bad_inputs, s.exchanges) << "every exchange was invalid";

  // The slave sends positions again: valid, the age from the last valid input.
  rig.emulator->set_inputs_all_ones(false);
  rig.run_for(10ms);
  EXPECT_TRUE(cli::encoder_inputs_valid(s));
  const auto again = cli::encoder_input_lines(session.lifecycle(), s);
  EXPECT_NE(again.find("last valid input"), std::string::npos) << again;
  EXPECT_NE(again.find("counts = 10.000 mm"), std::string::npos) << again;
}

TEST(EncoderStatus, ValidInputsAfterAValidOneTurnedInvalidKeepTheAgeOfTheValidOne) {
  Rig rig(Functionality::class2);
  Session& session = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << session.fault_reason();
  const Snapshot& s = session.snapshot();
  EXPECT_TRUE(cli::encoder_inputs_valid(s));
  rig.emulator->set_inputs_all_ones(true);
  rig.run_for(30ms);
  EXPECT_FALSE(cli::encoder_inputs_valid(s));
  EXPECT_GE(s.input_age, 25ms) << "the age runs on from the last valid input";
  EXPECT_NE(cli::encoder_input_lines(session.lifecycle(), s).find("last valid input"), std::string::npos);
}

}  // namespace
}  // namespace cellctl::encoder
