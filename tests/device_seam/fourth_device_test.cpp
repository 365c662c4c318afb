// A fourth kind of device, a made-up digital I/O module (dio_module.hpp), added through the registry's
// kinds alone: the cycle reads its link and hands it its intents, the monitor judges its link by its
// name, and the safe-stop stops it and gives its verdict beside the three devices of the cell.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "config/cell_config.hpp"
#include "device_seam/device_registry.hpp"
#include "dio_module.hpp"
#include "link/sim_link.hpp"
#include "monitor/monitor.hpp"
#include "runtime/cell_devices.hpp"
#include "runtime/emulated_cell.hpp"
#include "runtime/emulator_setup.hpp"
#include "runtime/safe_stop.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;

constexpr std::size_t kDioSlot = cell::kDevices;  // the first slot after the cell's own three

// The registry's kinds and the module's, in slot order.
std::vector<device_seam::DeviceKind> kinds_with_dio() {
  std::vector<device_seam::DeviceKind> kinds(device_seam::cell_device_kinds().begin(),
                                             device_seam::cell_device_kinds().end());
  kinds.push_back({"dio", &dio::make});
  return kinds;
}

class FourthDevice : public ::testing::Test {
 protected:
  FourthDevice()
      : cell_(config::load_cell_config(CELLCTL_SOURCE_DIR "/config/cell.yaml")),
        setup_(runtime::load_emulator_setup(cell_)),
        scu_line_(clock_, cell_.scu->port.line, "scu"),
        spindle_line_(clock_, cell_.spindle->port.line, "spindle"),
        encoder_line_(clock_, cell_.encoder->port.line, "encoder"),
        dio_line_(clock_, link::line_8n1(38400), "dio"),
        emulated_(cell_, setup_,
                  {.scu = &scu_line_.device(),
                   .spindle = &spindle_line_.device(),
                   .encoder = &encoder_line_.device()}),
        module_(dio_line_.device()),
        kinds_(kinds_with_dio()),
        links_{&scu_line_.master(), &spindle_line_.master(), &encoder_line_.master(), &dio_line_.master()},
        devices_(
            cell_, links_, [](std::size_t) { return true; }, kinds_),
        monitor_(cell_) {}

  // One control cycle as CellRun runs it.
  void cycle() {
    const auto now = clock_.now();
    emulated_.poll(now);
    module_.poll();
    devices_.receive(now);
    devices_.read(now, state_);
    if (safe_) safe_->observe(now, state_);
    fresh_ |= monitor_.evaluate(state_, {}, link::to_seconds(now - start_));
    if (safe_ && safe_->begun()) safe_->step(now, false);
    if (!safe_ || !safe_->begun()) devices_.apply(intents_);
    devices_.transmit(now);
    clock_.advance(1ms);
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
    start_ = clock_.now();
    safe_ = std::make_unique<runtime::SafeStop>(devices_, 5s, start_);
    devices_.activate(start_);
    ASSERT_TRUE(cycle_until([&] {
      for (std::size_t d = 0; d <= kDioSlot; ++d)
        if (!state_.links[d].active || state_.links[d].counts.good_replies == 0) return false;
      return state_.encoder.data_exchange;
    })) << "every device, the module among them, in its active state";
  }
  runtime::Verdicts stop_and_judge() {
    safe_->begin(clock_.now());
    EXPECT_TRUE(cycle_until([&] { return safe_->done(); })) << "the safe-stop resolves every device";
    return safe_->verdicts();
  }

  link::VirtualClock clock_;
  config::CellConfig cell_;
  runtime::EmulatorSetup setup_;
  link::SimLink scu_line_;
  link::SimLink spindle_line_;
  link::SimLink encoder_line_;
  link::SimLink dio_line_;
  runtime::EmulatedCell emulated_;
  dio::Emulator module_;
  std::vector<device_seam::DeviceKind> kinds_;
  std::array<link::Link*, 4> links_;
  runtime::CellDevices devices_;
  monitor::Monitor monitor_;
  std::bitset<monitor::kRuleCount> fresh_;
  cell::CellState state_;
  cell::Intents intents_;
  link::TimePoint start_{};
  std::unique_ptr<runtime::SafeStop> safe_;
};

TEST_F(FourthDevice, IsInTheCycleWithItsLinkItsIntentsAndItsName) {
  start_up();
  EXPECT_EQ(state_.devices[kDioSlot], "dio");
  ASSERT_EQ(devices_.devices().size(), 4u);
  EXPECT_EQ(devices_.devices()[3]->slot(), kDioSlot);

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
