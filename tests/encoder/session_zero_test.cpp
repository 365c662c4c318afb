// The encoder's zero (issue 10, part 4): positions read signed around the encoder's output zero, so
// an axis below the native zero reads a little below 0 mm, not ≈ 16 384 mm; the configured zero
// offset; a stored preset offset the config does not expect faults the session at start-up; and a
// re-parameterisation (what Teach-In switches) over the same session.
#include <gtest/gtest.h>

#include <filesystem>

#include "encoder/commissioning_parameters.hpp"
#include "session_rig.hpp"

namespace cellctl::encoder {
namespace {

using namespace std::chrono_literals;
using link::Lifecycle;
using testing::Rig;

TEST(EncoderZero, AnAxisCrossingTheNativeZeroReadsNegativeNotTheWholeRange) {
  Rig rig;
  rig.move_to(2.0);
  auto& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging() && s.snapshot().input_valid; }, 2s));
  EXPECT_NEAR(s.snapshot().position_mm, 2.0, 0.01);
  // Down through the native zero at 1 mm/s: every reading on the way is within a step of the axis.
  rig.axis_start_mm = 2.0;
  rig.axis_speed_mm_s = -1.0;
  rig.moving_since = rig.clock.now();
  double worst = 0.0;
  for (int i = 0; i < 40; ++i) {
    rig.run_for(100ms);
    worst = std::max(worst, std::abs(s.snapshot().position_mm - rig.axis_mm()));
  }
  EXPECT_LT(rig.axis_mm(), -1.5);
  EXPECT_NEAR(s.snapshot().position_mm, rig.axis_mm(), 0.05);
  EXPECT_LT(worst, 0.05) << "a reading near the native zero jumped by the range (16384 mm)";
  // The raw counts did wrap: the encoder sends the top of its range.
  EXPECT_GT(s.snapshot().position_counts, (1u << 25) - 10000u);
}

TEST(EncoderZero, TheConfiguredZeroOffsetIsTakenOff) {
  Rig rig;
  rig.session_config.zero_offset_mm = 5.0;
  rig.move_to(12.0);
  auto& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging() && s.snapshot().input_valid; }, 2s));
  EXPECT_NEAR(s.snapshot().position_mm, 7.0, 0.01);
}

TEST(EncoderZero, AStoredPresetOffsetTheConfigDoesNotExpectFaultsTheStartUpWithBothValues) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "encoder_zero_offset_check";
  std::filesystem::create_directories(dir);
  const auto state = dir / "encoder.eeprom";
  std::filesystem::remove(state);
  {
    // A preset to 1000 counts (what `cellctl encoder preset 1000` does), kept in the EEPROM.
    Rig rig(Functionality::scancon22, 5, state);
    rig.move_to(10.0);
    auto& s = rig.start();
    ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 2s));
    ASSERT_TRUE(s.preset(1000));
    ASSERT_TRUE(rig.run_until([&] { return s.snapshot().command.phase == Handshake::Phase::done; }, 2s));
    rig.run_for(50ms);
  }
  Rig rig(Functionality::scancon22, 5, state);
  rig.session_config.expected_offset = 0;  // the config was written before the preset
  rig.move_to(10.0);
  auto& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return s.lifecycle() == Lifecycle::fault; }, 2s));
  EXPECT_NE(s.fault_reason().find("preset offset -19480"), std::string::npos) << s.fault_reason();
  EXPECT_NE(s.fault_reason().find("preset_offset: 0"), std::string::npos) << s.fault_reason();
  rig.run_for(300ms);
  EXPECT_FALSE(s.snapshot().data_exchange) << "positions of a shifted encoder must not reach the cell";
  EXPECT_EQ(s.lifecycle(), Lifecycle::fault);

  // With the offset recorded, the same encoder starts and reads the preset position.
  Rig recorded(Functionality::scancon22, 5, state);
  recorded.session_config.expected_offset = -19480;
  recorded.move_to(10.0);
  auto& r = recorded.start();
  ASSERT_TRUE(recorded.run_until([&] { return recorded.exchanging() && r.snapshot().input_valid; }, 2s));
  EXPECT_EQ(r.snapshot().position_counts, 1000u);
  EXPECT_EQ(r.lifecycle(), Lifecycle::active);
}

TEST(EncoderZero, ReconfigureSendsTheTeachInPrerequisitesAndBack) {
  Rig rig;
  rig.move_to(10.0);
  auto& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging() && s.snapshot().input_valid; }, 2s));
  EXPECT_FALSE(s.reconfigure(rig.session_config)) << "only while closed";
  auto teach = rig.session_config;
  teach.parameters = teach_in_parameters(teach.parameters, teach.physical);
  s.deactivate(rig.clock.now());
  ASSERT_TRUE(rig.run_until([&] { return s.quiet(); }, 2s));
  ASSERT_TRUE(s.reconfigure(teach));
  s.activate(rig.clock.now());
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging() && s.snapshot().input_valid; }, 2s));
  EXPECT_TRUE(s.snapshot().status.commissioning);
  EXPECT_NEAR(s.snapshot().position_mm, 10.0, 0.01);
  EXPECT_TRUE(rig.emulator->device().parameters().scaling);
  EXPECT_EQ(rig.emulator->device().parameters().units_select, UnitsSelect::per_total_range);
  EXPECT_TRUE(s.teach_in_start());

  s.deactivate(rig.clock.now());
  ASSERT_TRUE(rig.run_until([&] { return s.quiet(); }, 2s));
  ASSERT_TRUE(s.reconfigure(rig.session_config));
  s.activate(rig.clock.now());
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging() && s.snapshot().input_valid; }, 2s));
  EXPECT_FALSE(s.snapshot().status.commissioning);
  EXPECT_FALSE(rig.emulator->device().teach_in_running()) << "re-parameterisation ends a Teach-In begun";
  EXPECT_EQ(rig.emulator->device().parameters(), rig.session_config.parameters);
}

}  // namespace
}  // namespace cellctl::encoder
