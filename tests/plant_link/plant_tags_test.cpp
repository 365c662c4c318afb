// What the plant's tags say, from the run's events (CellMirror, no broker): only a recipe's run counts
// as processed, a recipe's run that ends Stopped or Aborted as defective; the status's numbers are given
// to their devices' resolution; Idle's status carries the positions the last job left.

#include "schema/plant_tags.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "journal/event.hpp"
#include "plant_link/cell_mirror.hpp"
#include "plant_link/run_event.hpp"
#include "plant_link/tag_resolution.hpp"
#include "plant_test_support.hpp"

namespace cellctl::plant_link {
namespace {

using namespace journal;

config::CellCore cell() {
  config::CellCore c;
  c.name = "c";
  c.axes.resize(2);
  c.axes[0].name = "x";
  c.axes[0].edges_per_mm = 10.0;  // the default cell's: 0.1 mm
  c.axes[1].name = "z";
  c.axes[1].edges_per_mm = 100.0;
  return c;
}

using Counts = std::pair<std::uint64_t, std::uint64_t>;  // processed, defective

class PlantTags : public ::testing::Test {
 protected:
  void feed(double t, const Payload& p) {
    if (const auto e = run_event_of({t, p})) (void)mirror_.apply(*e);
  }
  // A job from its start to its end state.
  void job(std::string_view job, std::string_view end) {
    feed(0.0, RunStarted{"r", "c", "virtual-time", 1, job});
    feed(0.0, StateChanged{"Idle", "Starting", Text::format("start by plant")});
    feed(0.1, StateChanged{"Starting", "Execute", {}});
    feed(0.5, StateChanged{"Execute", end, {}});
    feed(0.5, RunEnded{"ended"});
  }
  [[nodiscard]] Counts counts() const {
    return {mirror_.admin_tag().processed, mirror_.admin_tag().defective};
  }

  CellMirror mirror_{cell(), "virtual-time"};
};

TEST_F(PlantTags, OnlyRecipesAreProcessedAndTheirStopsAndAbortsDefective) {
  job("recipe", "Complete");
  EXPECT_EQ(counts(), Counts(1, 0));
  job("homing", "Complete");
  job("teach-in", "Complete");
  job("homing", "Aborted");
  job("teach-in", "Stopped");
  EXPECT_EQ(counts(), Counts(1, 0)) << "a homing or a Teach-In counted";
  job("recipe", "Stopped");
  job("recipe", "Aborted");
  EXPECT_EQ(counts(), Counts(1, 2));
  // The arbiter's own stop between jobs is no run: nothing more is counted.
  feed(0.0, StateChanged{"Aborted", "Stopping", Text::format("stop by terminal")});
  feed(0.0, StateChanged{"Stopping", "Stopped", Text::format("no job was in progress: nothing moved")});
  EXPECT_EQ(counts(), Counts(1, 2));
  const auto admin = nlohmann::json::parse(schema::admin_payload(mirror_.admin_tag()));
  EXPECT_EQ(admin["ProdProcessedCount"], 1);
  EXPECT_EQ(admin["ProdDefectiveCount"], 2);
}

TEST_F(PlantTags, StatusNumbersAreGivenToTheirDevicesResolutionAndIdleKeepsThePositions) {
  feed(0.0, RunStarted{"r", "c", "virtual-time", 1, "recipe"});
  Sample s;
  s.axes = 2;
  s.planned_mm = {20.6f, -0.00004f};
  s.scu_mm = {20.64f, 7.123f};
  s.encoder_mm = 20.612345f;
  s.spindle_set_hz = 400.0f;
  s.spindle_actual_hz = 399.7f;
  feed(0.2, s);
  feed(0.5, StateChanged{"Execute", "Complete", {}});
  feed(0.6, StateChanged{"Complete", "Resetting", Text::format("reset by plant")});
  feed(0.6, StateChanged{"Resetting", "Idle", Text::format("reset done")});
  LiveStatus live;  // no run in progress
  live.jitter_max_us = 53.2468;
  const auto payload = schema::status_payload(mirror_.status_tag(live));
  const auto j = nlohmann::json::parse(payload);
  EXPECT_EQ(j["state"], "Idle");
  // x: 0.1 mm (10 edges/mm), z: 0.01 mm (100 edges/mm); never -0.
  EXPECT_EQ(j["axes"][0].dump(), R"({"measured_mm":20.6,"name":"x","planned_mm":20.6})");
  EXPECT_EQ(j["axes"][1].dump(), R"({"measured_mm":7.12,"name":"z","planned_mm":0.0})");
  EXPECT_EQ(j["encoder_mm"].dump(), "20.6123");
  EXPECT_EQ(j["spindle"].dump(), R"({"actual_hz":400.0,"set_hz":400.0})");
  EXPECT_EQ(j["jitter_max_us"].dump(), "53.2");
  EXPECT_FALSE(cellctl::testing::has_long_fraction(payload)) << payload;
}

TEST(TagResolution, PositionDecimalsResolveOneSCUEdge) {
  config::AxisConfig a;
  a.edges_per_mm = 10.0;
  EXPECT_EQ(position_decimals(a), 1);
  a.edges_per_mm = 100.0;
  EXPECT_EQ(position_decimals(a), 2);
  a.edges_per_mm = 3.0;  // a third of a mm: tenths resolve it
  EXPECT_EQ(position_decimals(a), 1);
  a.edges_per_mm = 0.0;  // no scaling known
  EXPECT_EQ(position_decimals(a), 3);
  EXPECT_EQ(nlohmann::json(to_decimals(static_cast<double>(20.6f), 1)).dump(), "20.6");
  EXPECT_EQ(nlohmann::json(to_decimals(-0.00004, 2)).dump(), "0.0");
}

}  // namespace
}  // namespace cellctl::plant_link
