// The cell config's cross-checks on link silence: limits.link_silence_ms must exceed every device's
// normal spacing of good replies (SCU keep-alive + reply time-out, spindle status poll + reply
// time-out, the encoder's DP lost-slave time), or a healthy cell stops with category 0 mid-run.

#include "config/cell_checks.hpp"

#include <gtest/gtest.h>

#include <string>

#include "config/cell_config.hpp"
#include "support/expect_config_error.hpp"

namespace cellctl::config {
namespace {

// Lines 1–3; `limits` is line 4 when given, the devices follow.
const std::string kAxes = R"(cell: t
axes:
  - {name: x, actuator: 1, function: 1, min_mm: 0, max_mm: 100, max_speed_mm_s: 10, encoder: true}
)";

std::string scu(int keepalive_ms, int reply_timeout_ms) {
  return "scu:\n  keepalive_ms: " + std::to_string(keepalive_ms) +
         "\n  reply_timeout_ms: " + std::to_string(reply_timeout_ms) +
         "\n  actuators: [{index: 1, edges_per_mm: 10, stroke_mm: 100, max_speed_mm_s: 10}]\n";
}
std::string spindle(int status_poll_ms, int reply_timeout_ms) {
  return "spindle: {status_poll_ms: " + std::to_string(status_poll_ms) +
         ", reply_timeout_ms: " + std::to_string(reply_timeout_ms) + "}\n";
}
std::string encoder(int lost_after_ms) {
  return "encoder: {mm_per_revolution: 4, time_base: steps_per_10ms, lost_after_ms: " +
         std::to_string(lost_after_ms) + "}\n";
}
std::string silence(int ms) {
  return "limits: {link_silence_ms: " + std::to_string(ms) + "}\n";
}

CellConfig parse(const std::string& text) {
  return parse_cell_config(YamlNode::load_string(text, "cell.yaml"), "cell.yaml");
}

void expect_error(const std::string& text, const std::string& message) {
  cellctl::testing::expect_config_error([&] { (void)parse(text); }, message);
}

TEST(CellLinkSilence, ShippedTimingsPass) {
  // 100 + 150 ms, 20 + 100 ms and 100 ms, all inside 300 ms.
  const auto cell = parse(kAxes + silence(300) + scu(100, 150) + spindle(20, 100) + encoder(100));
  EXPECT_DOUBLE_EQ(cell.limits.link_silence_ms, 300.0);
  EXPECT_NO_THROW((void)load_cell_config(CELLCTL_SOURCE_DIR "/config/cell.yaml"));
  EXPECT_NO_THROW((void)load_cell_config(CELLCTL_SOURCE_DIR "/config/examples/cell-hardware.yaml"));
}

TEST(CellLinkSilence, ScuKeepAlivePlusReplyTimeOutMustFitInside) {
  expect_error(kAxes + silence(300) + scu(200, 150) + spindle(20, 100) + encoder(100),
               "cell.yaml:4:27: limits.link_silence_ms: 300 ms must exceed the scu's normal reply spacing "
               "(keep-alive 200 ms + reply time-out 150 ms = 350 ms): a healthy scu would be taken for a "
               "silent link");
  // Equal is not enough: a reply due at the very end of the spacing would already be late.
  expect_error(kAxes + silence(250) + scu(100, 150) + encoder(100),
               "cell.yaml:4:27: limits.link_silence_ms: 250 ms must exceed the scu's normal reply spacing "
               "(keep-alive 100 ms + reply time-out 150 ms = 250 ms): a healthy scu would be taken for a "
               "silent link");
  EXPECT_NO_THROW((void)parse(kAxes + silence(251) + scu(100, 150) + encoder(100)));
}

TEST(CellLinkSilence, SpindleStatusPollPlusReplyTimeOutMustFitInside) {
  expect_error(kAxes + silence(300) + scu(100, 150) + spindle(250, 100) + encoder(100),
               "cell.yaml:4:27: limits.link_silence_ms: 300 ms must exceed the spindle's normal reply "
               "spacing (status poll 250 ms + reply time-out 100 ms = 350 ms): a healthy spindle would be "
               "taken for a silent link");
}

TEST(CellLinkSilence, EncoderLostSlaveTimeMustFitInside) {
  expect_error(kAxes + silence(300) + scu(100, 150) + spindle(20, 100) + encoder(400),
               "cell.yaml:4:27: limits.link_silence_ms: 300 ms must exceed the encoder's normal reply "
               "spacing (DP lost-slave time 400 ms): a healthy encoder would be taken for a silent link");
}

TEST(CellLinkSilence, WithTheDefaultSilenceTheDeviceSectionIsBlamed) {
  // No limits.link_silence_ms: the default 300 ms applies, and the spindle's section is where a
  // too-slow poll was chosen.
  expect_error(kAxes + scu(100, 150) + spindle(250, 100) + encoder(100),
               "cell.yaml:8:10: spindle: the normal reply spacing (status poll 250 ms + reply time-out "
               "100 ms = 350 ms) must be shorter than limits.link_silence_ms (300 ms, the default): a "
               "healthy spindle would be taken for a silent link");
}

// The encoder's 16-bit velocity saturates at 32767: with 2048 counts/mm (8192 steps, 4 mm per
// revolution) the overspeed limit 25 mm/s is 51200 steps/s, which steps_per_s cannot carry.
TEST(CellEncoderTimeBase, AVelocityTimeBaseThatSaturatesBelowTheOverspeedLimitIsRefused) {
  const std::string axes_scu = kAxes + scu(100, 150);
  expect_error(
      axes_scu + "encoder: {mm_per_revolution: 4, time_base: steps_per_s}\n",
      "cell.yaml:8:44: encoder.time_base: the overspeed limit 25 mm/s is 51200 units/s = 51200 in "
      "steps_per_s, beyond the encoder's 16-bit velocity (at most 32767, manual 4.3.4/4.3.5): it would "
      "saturate and an overspeed would go unseen; time bases that fit (value at the limit): "
      "steps_per_100ms (5120), steps_per_10ms (512), rpm (375)");
  // Not given, the manual's default (steps per second) is the one refused, at the section.
  expect_error(axes_scu + "encoder: {mm_per_revolution: 4}\n",
               "cell.yaml:8:10: encoder: time_base steps_per_s (the default): the overspeed limit 25 mm/s is "
               "51200 units/s = 51200 in steps_per_s, beyond the encoder's 16-bit velocity (at most 32767, "
               "manual 4.3.4/4.3.5): it would saturate and an overspeed would go unseen; time bases that fit "
               "(value at the limit): steps_per_100ms (5120), steps_per_10ms (512), rpm (375)");
  // A lower limit fits: 15 mm/s is 30720 steps/s.
  EXPECT_NO_THROW((void)parse(kAxes + "limits: {overspeed_mm_s: 15}\n" + scu(100, 150) +
                              "encoder: {mm_per_revolution: 4, time_base: steps_per_s}\n"));
  // Class 2 and Scancon 2.1 have no velocity: nothing to saturate.
  EXPECT_NO_THROW((void)parse(
      axes_scu + "encoder: {mm_per_revolution: 4, functionality: scancon2.1, time_base: steps_per_s}\n"));
}

TEST(CellEncoderTimeBase, Scancon30AccelerationMustFitToo) {
  // 40 mm/s² (the axis default) × 2048 counts/mm over a 1 s sample: 81920 per sample.
  expect_error(
      kAxes + "limits: {overspeed_mm_s: 10}\n" + scu(100, 150) +
          "encoder: {mm_per_revolution: 4, functionality: scancon3.0, time_base: steps_per_s}\n",
      "cell.yaml:9:71: encoder.time_base: axis acceleration 40 mm/s² changes the velocity by 81920 per "
      "steps_per_s sample, beyond the encoder's 16-bit acceleration (at most 32767, manual "
      "4.3.4/4.3.5): it would saturate and an overspeed would go unseen; time bases that fit (value "
      "at the limit): steps_per_100ms (2048), steps_per_10ms (205), rpm (150)");
}

}  // namespace
}  // namespace cellctl::config
