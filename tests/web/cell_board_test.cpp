// The page's board: each axis's target, SCU and encoder positions and its two homed facts kept apart;
// every device slot the cell state names listed by its name (a fourth device too), an empty slot
// left out; a view from a job that has ended marked as not live. Its JSON, made by the schema
// (schema/page_payloads.hpp), byte for byte as the page made it before it moved there.
#include "web/cell_board.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "web/command_buttons.hpp"

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

// The board's JSON as the page sends it, read back.
nlohmann::json board_payload(const std::vector<std::string>& names,
                             const std::optional<status::StatusView>& view, bool live) {
  return nlohmann::json::parse(schema::board_json(board_view(names, view, live)));
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

// What the page sent before its JSON moved into the schema (web/cell_board.cpp's JSON with the page's
// state, PackML number, buttons and history added, dumped), for these views: the same bytes.
TEST(CellBoard, TheJsonIsTheSameBytesAsBeforeTheSchemaMadeIt) {
  auto idle = board_view({"x", "z"}, two_axes(), true);
  idle.state = "Idle";
  idle.state_current = 4;
  idle.buttons = command_buttons("Idle", true);
  idle.history = true;
  EXPECT_EQ(schema::board_json(idle),
            R"({"axes":[{"encoder_mm":39.88,"homed":{"record":true,"scu":false},"name":"x","scu_mm":39.91)"
            R"(0000000000004,"target_mm":40.0},{"encoder_mm":null,"homed":{"record":false,"scu":true},"na)"
            R"(me":"z","scu_mm":5.0,"target_mm":null}],"buttons":{"abort":{"enabled":true},"clear":{"enab)"
            R"(led":false,"reason":"clear is taken only in Aborted"},"hold":{"enabled":false,"reason":"ho)"
            R"(ld is taken only in Execute"},"home":{"enabled":true},"reset":{"enabled":false,"reason":"n)"
            R"(othing to reset"},"start":{"enabled":true},"stop":{"enabled":true},"teach-in":{"enabled":t)"
            R"(rue},"unhold":{"enabled":false,"reason":"unhold is taken only in Held or Holding"}},"devic)"
            R"(es":[{"bad_frames":0,"last_good_s":0.0,"link":"up","name":"scu","refusals":0,"replies":0,")"
            R"(round_trip_ms":11.5,"timeouts":0},{"bad_frames":0,"last_good_s":0.0,"link":"lost","name":")"
            R"(encoder","refusals":0,"replies":0,"round_trip_ms":0.0,"timeouts":0},{"bad_frames":2,"last_)"
            R"(good_s":0.25,"link":"up","name":"dio","refusals":3,"replies":7,"round_trip_ms":0.0,"timeou)"
            R"(ts":1}],"history":true,"live":true,"spindle":{"actual_hz":0.0,"set_hz":0.0},"state":"Idle")"
            R"(,"state_current":4,"t":12.346})");
  auto aborted = board_view({"x", "z"}, std::nullopt, true);
  aborted.state = "Aborted";
  aborted.state_current = 9;
  aborted.buttons = command_buttons("Aborted", false);
  EXPECT_EQ(schema::board_json(aborted),
            R"({"axes":[{"name":"x"},{"name":"z"}],"buttons":{"abort":{"enabled":false,"reason":"the cell)"
            R"( is aborting or aborted already"},"clear":{"enabled":true},"hold":{"enabled":false,"reason)"
            R"(":"hold is taken only in Execute"},"home":{"enabled":false,"reason":"this cellctl drives o)"
            R"(ne run (cellctl run): jobs start under cellctl serve"},"reset":{"enabled":false,"reason":")"
            R"(clear first: Aborted takes Clear, then Reset"},"start":{"enabled":false,"reason":"this cel)"
            R"(lctl drives one run (cellctl run): jobs start under cellctl serve"},"stop":{"enabled":fals)"
            R"(e,"reason":"the cell is stopping or stopped already"},"teach-in":{"enabled":false,"reason")"
            R"(:"this cellctl drives one run (cellctl run): jobs start under cellctl serve"},"unhold":{"e)"
            R"(nabled":false,"reason":"unhold is taken only in Held or Holding"}},"devices":[],"history":)"
            R"(false,"live":false,"state":"Aborted","state_current":9})");
  auto at_start = two_axes();
  at_start.safe[0] = "observed";
  auto read = board_view({"x", "z"}, at_start, false);
  read.read_at_start = true;
  read.state = "Idle";
  read.state_current = 4;
  read.buttons = command_buttons("Idle", true);
  read.history = true;
  EXPECT_EQ(schema::board_json(read),
            R"({"axes":[{"encoder_mm":39.88,"homed":{"record":true,"scu":false},"name":"x","scu_mm":39.91)"
            R"(0000000000004,"target_mm":40.0},{"encoder_mm":null,"homed":{"record":false,"scu":true},"na)"
            R"(me":"z","scu_mm":5.0,"target_mm":null}],"buttons":{"abort":{"enabled":true},"clear":{"enab)"
            R"(led":false,"reason":"clear is taken only in Aborted"},"hold":{"enabled":false,"reason":"ho)"
            R"(ld is taken only in Execute"},"home":{"enabled":true},"reset":{"enabled":false,"reason":"n)"
            R"(othing to reset"},"start":{"enabled":true},"stop":{"enabled":true},"teach-in":{"enabled":t)"
            R"(rue},"unhold":{"enabled":false,"reason":"unhold is taken only in Held or Holding"}},"devic)"
            R"(es":[{"bad_frames":0,"last_good_s":0.0,"link":"up","name":"scu","refusals":0,"replies":0,")"
            R"(round_trip_ms":11.5,"safe":"observed","timeouts":0},{"bad_frames":0,"last_good_s":0.0,"lin)"
            R"(k":"lost","name":"encoder","refusals":0,"replies":0,"round_trip_ms":0.0,"timeouts":0},{"ba)"
            R"(d_frames":2,"last_good_s":0.25,"link":"up","name":"dio","refusals":3,"replies":7,"round_tr)"
            R"(ip_ms":0.0,"timeouts":1}],"history":true,"live":false,"read_at_start":true,"spindle":{"act)"
            R"(ual_hz":0.0,"set_hz":0.0},"state":"Idle","state_current":4,"t":12.346})");
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
