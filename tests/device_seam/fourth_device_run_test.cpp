// The fourth kind of device (the I/O module of dio_module.hpp) in whole runs, as a user meets it:
// registered by its DeviceKind and named by a dio: section, it is on a line of its own with its
// emulator in a virtual-time CellRun; the recipe's spindle opens its coolant valve; the run's summary
// gives its safe-stop verdict and its link's figures beside the cell's three, the operator page's board
// and /metrics list it; a rehearsed fault names
// it, and its loss ends the run as a link fault named after it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "dio_module.hpp"
#include "integration/run_fixture.hpp"
#include "support/http_get.hpp"
#include "web/cell_board.hpp"
#include "web/operator_page.hpp"

namespace cellctl::testing {
namespace {

const std::string kRecipe = demo_recipe("coolant", R"(  - name: spindle up
    spindle: {start_hz: 400, direction: cw}
  - {name: cut, dwell: 1.0}
  - name: spindle down
    spindle: stop
)");

class FourthDeviceRun : public RunFixture {
 protected:
  void SetUp() override {
    RunFixture::SetUp();
    device_kinds_ = kinds_;
    cell_ = dio::cell_with(dio::kDioSection, kinds_);
    load_recipe_text(kRecipe);
  }
  nlohmann::json summary() const { return events("summary").at(0); }

  std::vector<device_seam::DeviceKind> kinds_ = dio::kinds_with_dio();
};

TEST_F(FourthDeviceRun, ItsValveFollowsTheSpindleAndTheSummaryJudgesItBesideTheCellsThree) {
  auto& run = make_run();
  bool valve_opened = false;
  run.on_cycle([&](double, runtime::CellRun& r) {
    if (auto* module = r.emulators()->find<dio::Emulator>(); module && module->outputs() == 0x01)
      valve_opened = true;
  });
  const auto result = go();
  EXPECT_EQ(result.final_state, supervisor::State::complete) << result.failure;
  EXPECT_TRUE(valve_opened) << "the coolant valve opened while the spindle ran";
  EXPECT_EQ(run.emulators()->find<dio::Emulator>()->outputs(), 0x00) << "and is shut at the end";

  const auto s = summary();
  for (const char* device : {"scu", "spindle", "encoder", "dio"})
    EXPECT_EQ(s["devices"][device]["safe"], "observed") << device << ": " << s["devices"][device];
  EXPECT_NE(s["devices"]["dio"]["evidence"].get<std::string>().find("every output off, read back at"),
            std::string::npos);
  ASSERT_TRUE(s["links"].contains("dio")) << "its link's figures in the summary: " << s["links"];
  EXPECT_GT(s["links"]["dio"]["replies"].get<long>(), 0) << s["links"]["dio"];

  // The operator page's board lists it among the devices, by its name, with its link's health.
  const auto board = web::board_view({"x", "z"}, run.status().read(), true);
  const auto& devices = board.devices;
  const auto dio =
      std::find_if(devices.begin(), devices.end(), [](const auto& d) { return d.name == "dio"; });
  ASSERT_NE(dio, devices.end()) << schema::board_json(board);
  EXPECT_EQ(devices.size(), 4u) << schema::board_json(board);
  EXPECT_GT(dio->replies, 0u) << schema::board_json(board);

  // And the page's /metrics, scraped as Prometheus does, has a series for it (by its name).
  command::Arbiter arbiter(std::chrono::milliseconds(1000), {});
  web::PageOptions options;
  options.port = 0;
  options.token = "fourth-device-test-token";
  web::OperatorPage page(options, cell_, plant_link::fixed_run(arbiter, run.status(), "virtual-time"));
  const auto metrics = http_get(page.port(), "/metrics", options.token);
  ASSERT_TRUE(metrics) << "the page answered nothing";
  const auto& [status, body] = *metrics;
  ASSERT_EQ(status, 200) << body;
  EXPECT_NE(body.find("cellctl_device_exchanges_total{device=\"dio\"} "), std::string::npos) << body;
  EXPECT_NE(body.find("cellctl_device_link_fault{device=\"dio\"} 0"), std::string::npos) << body;
  // Every series is typed (Prometheus takes one without its TYPE line as untyped), the counts of
  // recipe runs among them.
  std::istringstream lines(body);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == '#') continue;
    auto name = line.substr(0, line.find_first_of("{ "));
    for (const char* part : {"_bucket", "_sum", "_count"})
      if (name.ends_with(part) && body.find("# TYPE " + name.substr(0, name.size() - std::strlen(part)) +
                                            " histogram") != std::string::npos)
        name.resize(name.size() - std::strlen(part));
    EXPECT_NE(body.find("# TYPE " + name + " "), std::string::npos) << line;
  }
  EXPECT_NE(body.find("cellctl_defective_total 0"), std::string::npos) << body;
}

TEST_F(FourthDeviceRun, ARehearsedFaultNamesItAndItsLossEndsTheRunAsItsLinkFault) {
  auto spec = runtime::parse_fault_spec("dio:silent@0.5", kinds_);
  ASSERT_TRUE(std::holds_alternative<runtime::FaultSpec>(spec));
  faults_.push_back(std::get<runtime::FaultSpec>(spec));
  make_run();
  const auto result = go();
  EXPECT_NE(result.final_state, supervisor::State::complete);

  const auto injected = events("fault_injected");
  ASSERT_FALSE(injected.empty());
  EXPECT_EQ(injected[0]["device"], "dio");
  EXPECT_EQ(summary()["ended_by"]["kind"], "link") << summary()["ended_by"];
  EXPECT_EQ(summary()["ended_by"]["device"], "dio") << summary()["ended_by"];
  EXPECT_EQ(summary()["devices"]["dio"]["safe"], "unknown") << summary()["devices"]["dio"];
}

TEST_F(FourthDeviceRun, ItsOwnErrorIsItsEmulatorsInTheKindsWords) {
  auto spec = runtime::parse_fault_spec("dio:error@0.5+0.2", kinds_);
  ASSERT_TRUE(std::holds_alternative<runtime::FaultSpec>(spec));
  const auto& fault = std::get<runtime::FaultSpec>(spec);
  EXPECT_EQ(runtime::FaultRehearsal::what(fault, kinds_),
            "the module stops answering (its watchdog tripped)");
  EXPECT_EQ(runtime::FaultRehearsal::what(fault), "?") << "a kind the cell's registry does not have";
  auto unknown = runtime::parse_fault_spec("dio:error@1");
  ASSERT_TRUE(std::holds_alternative<runtime::FaultSpecError>(unknown));
  EXPECT_EQ(std::get<runtime::FaultSpecError>(unknown).reason,
            "unknown device 'dio' (scu, spindle, encoder)");
}

}  // namespace
}  // namespace cellctl::testing
