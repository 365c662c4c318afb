// A fourth kind of device, a made-up digital I/O module (dio_module.hpp), added through one
// registration (its DeviceKind) and a section of the cell config: its line is opened and its emulator
// made with the cell's, the cycle reads its link and hands it its intents, the monitor judges its link
// by its name, and the safe-stop stops it and gives its verdict beside the three devices of the cell.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "dio_module.hpp"
#include "monitor/monitor.hpp"
#include "runtime/safe_stop.hpp"
#include "support/cell_rig.hpp"
#include "support/expect_config_error.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kDioSlot = cell::kDevices;  // the first slot after the cell's own three
using dio::kCellFile;

using dio::cell_with;
using dio::kDioSection;

class FourthDevice : public ::testing::Test {
 protected:
  FourthDevice()
      : kinds_(dio::kinds_with_dio()),
        rig_(cell_with(kDioSection, kinds_), kinds_),
        module_(*rig_.emulated.find<dio::Emulator>()),
        monitor_(rig_.cell) {}

  // One control cycle as CellRun runs it.
  void cycle() {
    const auto now = rig_.clock.now();
    rig_.receive();
    if (safe_) safe_->observe(now, rig_.state);
    fresh_ |= monitor_.evaluate(rig_.state, {}, link::to_seconds(now - start_));
    if (safe_ && safe_->begun()) {
      safe_->step(now, false);
      rig_.devices.transmit(now);
      rig_.clock.advance(1ms);
    } else {
      rig_.transmit(intents_);
    }
  }
  template <class Done>
  bool cycle_until(Done&& done, int limit = 20000) {
    for (int i = 0; i < limit; ++i) {
      cycle();
      if (done()) return true;
    }
    return false;
  }
  void start_up() {
    start_ = rig_.clock.now();
    safe_ = std::make_unique<runtime::SafeStop>(rig_.devices, 5s, start_);
    rig_.devices.activate(start_);
    ASSERT_TRUE(cycle_until([&] {
      for (std::size_t d = 0; d <= kDioSlot; ++d)
        if (!rig_.state.links[d].active || rig_.state.links[d].counts.good_replies == 0) return false;
      return rig_.state.encoder.data_exchange;
    })) << "every device, the module among them, in its active state";
  }
  runtime::Verdicts stop_and_judge() {
    safe_->begin(rig_.clock.now());
    EXPECT_TRUE(cycle_until([&] { return safe_->done(); })) << "the safe-stop resolves every device";
    return safe_->verdicts();
  }

  std::vector<device_seam::DeviceKind> kinds_;
  CellRig rig_;
  dio::Emulator& module_;
  monitor::Monitor monitor_;
  std::bitset<monitor::kRuleCount> fresh_;
  cell::Intents intents_;
  link::TimePoint start_{};
  std::unique_ptr<runtime::SafeStop> safe_;
};

TEST_F(FourthDevice, ItsSectionNamesItsPortAndAProblemThereIsTheConfigsError) {
  const auto port = dio::kKind.port(rig_.cell);
  ASSERT_TRUE(port.has_value());
  EXPECT_TRUE(port->emulated());
  EXPECT_EQ(port->line.baud, 38400u);
  EXPECT_FALSE(dio::kKind.port(device_seam::load_cell_config(kCellFile)).has_value())
      << "no section, no device";

  const auto lines = std::count(std::istreambuf_iterator<char>(std::ifstream(kCellFile).rdbuf()), {}, '\n');
  expect_config_error(
      [&] { (void)cell_with("dio:\n  port: emulated\n  bauds: 9600\n", kinds_); },
      fmt::format("{}:{}:3: dio.bauds: unknown field (did you mean 'baud'?)", kCellFile, lines + 3));
  expect_config_error([&] { (void)cell_with(kDioSection, device_seam::cell_device_kinds()); },
                      fmt::format("{}:{}:1: dio: unknown field", kCellFile, lines + 1));
}

TEST_F(FourthDevice, IsInTheCycleWithItsLinkItsIntentsAndItsName) {
  start_up();
  EXPECT_EQ(rig_.state.devices[kDioSlot], "dio");
  ASSERT_EQ(rig_.devices.devices().size(), 4u);
  EXPECT_EQ(rig_.devices.devices()[3]->slot(), kDioSlot);

  // Its part of the intents: the coolant valve opens with the spindle and closes when it stops.
  intents_.spindle = {.run = true, .frequency_hz = 500.0, .clockwise = true, .reset = false};
  ASSERT_TRUE(cycle_until([&] { return module_.outputs() == 0x01; }, 2000));
  intents_.spindle.run = false;
  ASSERT_TRUE(cycle_until([&] { return module_.outputs() == 0x00; }, 2000));
}

TEST_F(FourthDevice, ASilentModuleIsALinkFaultThatNamesIt) {
  start_up();
  monitor_.arm();
  fresh_.reset();
  module_.set_silent(true);
  ASSERT_TRUE(
      cycle_until([&] { return fresh_.test(static_cast<std::size_t>(monitor::Rule::link_silent)); }, 2000));
  const auto detail = std::string(monitor_.latch(monitor::Rule::link_silent).detail.view());
  EXPECT_EQ(detail.rfind("dio ", 0), 0u) << detail;
}

TEST_F(FourthDevice, TheSafeStopStopsItAndGivesItsVerdictBesideTheCellsOwn) {
  start_up();
  intents_.spindle = {.run = true, .frequency_hz = 500.0, .clockwise = true, .reset = false};
  ASSERT_TRUE(cycle_until([&] { return module_.outputs() == 0x01; }, 2000));

  const auto verdicts = stop_and_judge();
  ASSERT_TRUE(verdicts[kDioSlot].has_value());
  EXPECT_EQ(verdicts[kDioSlot]->device, "dio");
  EXPECT_EQ(verdicts[kDioSlot]->safe, runtime::Safe::observed) << verdicts[kDioSlot]->evidence;
  EXPECT_NE(verdicts[kDioSlot]->evidence.find("every output off, read back at"), std::string::npos);
  EXPECT_EQ(module_.outputs(), 0x00);
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    ASSERT_TRUE(verdicts[d].has_value()) << d;
    EXPECT_EQ(verdicts[d]->safe, runtime::Safe::observed)
        << verdicts[d]->device << ": " << verdicts[d]->evidence;
  }
}

TEST_F(FourthDevice, AModuleThatNeverAnswersTheStopIsUnknownAndSaysWhy) {
  start_up();
  intents_.spindle = {.run = true, .frequency_hz = 500.0, .clockwise = true, .reset = false};
  ASSERT_TRUE(cycle_until([&] { return module_.outputs() == 0x01; }, 2000));
  module_.set_silent(true);

  const auto verdicts = stop_and_judge();
  ASSERT_TRUE(verdicts[kDioSlot].has_value());
  EXPECT_EQ(verdicts[kDioSlot]->safe, runtime::Safe::unknown);
  EXPECT_NE(verdicts[kDioSlot]->evidence.find("I/O module lost at"), std::string::npos)
      << verdicts[kDioSlot]->evidence;
  EXPECT_NE(verdicts[kDioSlot]->evidence.find("coolant valve may still be open"), std::string::npos);
  EXPECT_EQ(verdicts[static_cast<std::size_t>(cell::Device::scu)]->safe, runtime::Safe::observed);
}

}  // namespace
}  // namespace cellctl::testing
