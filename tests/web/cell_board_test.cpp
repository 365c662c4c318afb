// The page's board: each axis's target, SCU and encoder positions and its two homed facts kept apart;
// every device slot the cell state names listed by its name (a fourth device too), an empty slot
// left out; a view from a job that has ended marked as not live.
#include "web/cell_board.hpp"

#include <gtest/gtest.h>

namespace cellctl::web {
namespace {

status::StatusView two_axes() {
  status::StatusView v;
  v.t = 12.3456;
  v.axes = 2;
  v.target_known = {true, false};
  v.target_mm = {40.0, 99.0};
  v.position_known = {true, true};
  v.scu_mm = {39.91, 5.0};
  v.encoder_measures = {true, false};
  v.encoder_mm = {39.8804, 77.0};
  v.home_recorded = {true, false};
  v.scu_initialised = {false, true};
  v.devices[0] = "scu";
  v.devices[2] = "encoder";
  v.devices[3] = "dio";  // a device the page code has never heard of
  v.link_active = {true, false, true, true};
  v.link_fault[2] = true;
  v.link_round_trip_s[0] = 0.01149;
  v.link_silent_s[3] = 0.25;
  v.link_counts[3] = {7, 1, 2, 3};
  return v;
}

TEST(CellBoard, EachAxisNamesTargetScuAndEncoderApartWithBothHomedFacts) {
  const auto b = board_payload({"x", "z"}, two_axes(), true);
  ASSERT_EQ(b["axes"].size(), 2u);
  const auto& x = b["axes"][0];
  EXPECT_EQ(x["name"], "x");
  EXPECT_DOUBLE_EQ(x["target_mm"].get<double>(), 40.0);
  EXPECT_DOUBLE_EQ(x["scu_mm"].get<double>(), 39.91);
  EXPECT_DOUBLE_EQ(x["encoder_mm"].get<double>(), 39.88);
  EXPECT_EQ(x["homed"], (nlohmann::json{{"record", true}, {"scu", false}}));
  const auto& z = b["axes"][1];
  EXPECT_TRUE(z["target_mm"].is_null()) << "no move asked for: no target";
  EXPECT_TRUE(z["encoder_mm"].is_null()) << "the encoder does not measure z";
  EXPECT_EQ(z["homed"], (nlohmann::json{{"record", false}, {"scu", true}}));
  EXPECT_TRUE(b["live"].get<bool>());
  EXPECT_DOUBLE_EQ(b["t"].get<double>(), 12.346);
}

TEST(CellBoard, EveryNamedSlotIsADeviceWithItsLinkAndAnEmptySlotIsNone) {
  const auto b = board_payload({"x", "z"}, two_axes(), true);
  ASSERT_EQ(b["devices"].size(), 3u);
  EXPECT_EQ(b["devices"][0]["name"], "scu");
  EXPECT_EQ(b["devices"][0]["link"], "up");
  EXPECT_DOUBLE_EQ(b["devices"][0]["round_trip_ms"].get<double>(), 11.5);
  EXPECT_EQ(b["devices"][1]["name"], "encoder");
  EXPECT_EQ(b["devices"][1]["link"], "lost");
  const auto& dio = b["devices"][2];
  EXPECT_EQ(dio["name"], "dio");
  EXPECT_EQ(dio["link"], "up");
  EXPECT_DOUBLE_EQ(dio["last_good_s"].get<double>(), 0.25);
  EXPECT_EQ(dio["replies"], 7);
  EXPECT_EQ(dio["timeouts"], 1);
  EXPECT_EQ(dio["bad_frames"], 2);
  EXPECT_EQ(dio["refusals"], 3);
}

TEST(CellBoard, ADeviceHasItsSafeStateOnceTheRunsStopResolvedIt) {
  auto v = two_axes();
  auto b = board_payload({"x", "z"}, v, true);
  for (const auto& d : b["devices"]) EXPECT_FALSE(d.contains("safe")) << "not resolved yet: " << d.dump();
  v.safe[0] = "observed";
  v.safe[2] = "unknown";
  b = board_payload({"x", "z"}, v, true);
  EXPECT_EQ(b["devices"][0]["safe"], "observed");
  EXPECT_EQ(b["devices"][1]["safe"], "unknown");
  EXPECT_FALSE(b["devices"][2].contains("safe"));
}

TEST(CellBoard, WithoutAViewTheAxesAreNamedAndNothingElseIsClaimed) {
  const auto b = board_payload({"x", "z"}, std::nullopt, true);
  EXPECT_FALSE(b["live"].get<bool>());
  ASSERT_EQ(b["axes"].size(), 2u);
  EXPECT_EQ(b["axes"][1], (nlohmann::json{{"name", "z"}}));
  EXPECT_TRUE(b["devices"].empty());
  EXPECT_FALSE(b.contains("t"));
  EXPECT_FALSE(board_payload({"x", "z"}, two_axes(), false)["live"].get<bool>()) << "an ended job's view";
}

}  // namespace
}  // namespace cellctl::web
