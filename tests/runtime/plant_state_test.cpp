// The emulated plant between dry runs (issue 22, item 2): an EmulatedCell built with a plant state
// file starts where the last one left the rods and with the SCU's initialised bits as it left them; a
// deliberate power cycle keeps the rods and loses the bits. Without a state file nothing is kept.
#include "runtime/plant_state.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "config/cell_config.hpp"
#include "link/clock.hpp"
#include "link/sim_link.hpp"
#include "runtime/dry_run_state.hpp"
#include "runtime/emulated_cell.hpp"

namespace cellctl::runtime {
namespace {

namespace fs = std::filesystem;

class PlantStateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cellctl-plant-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    cell_ = config::load_cell_config(fs::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // An SCU alone (no encoder, no spindle: nothing else to keep) over a SimLink nobody talks on.
  std::unique_ptr<EmulatedCell> scu_only(const emulation::EmulatorSetup& setup) {
    line_ = std::make_unique<link::SimLink>(clock_, cell_.scu->port.line);
    return std::make_unique<EmulatedCell>(cell_, setup, DeviceLinks{&line_->device()});
  }

  // Moves actuator a to `mm` at 10 mm/s, stepping the emulator on the virtual clock until it rests.
  void move(EmulatedCell& cell, int a, double mm) {
    auto& rod = cell.scu()->actuator(a);
    rod.move_to(mm, 10.0, true);
    for (int i = 0; i < 100000 && (rod.active() || rod.moving()); ++i) {
      clock_.advance(link::milliseconds(1));
      cell.poll(clock_.now());
    }
    ASSERT_NEAR(rod.position_mm(), mm, 0.01);
  }

  fs::path dir_;
  config::CellConfig cell_;
  link::VirtualClock clock_;
  std::unique_ptr<link::SimLink> line_;
};

TEST_F(PlantStateTest, TheNextDryRunStartsWhereTheLastLeftTheRodsAndTheirInitialisation) {
  const auto setup = dry_run_emulator_setup(cell_, dir_);
  {
    auto first = scu_only(setup);
    ASSERT_FALSE(first->scu()->initialised(1)) << "a fresh plant starts as after power-up";
    move(*first, 1, 10.0);
    move(*first, 1, 0.0);  // into the retracted end: the SCU initialises actuator 1
    move(*first, 1, 5.0);
    ASSERT_TRUE(first->scu()->initialised(1));
  }
  ASSERT_TRUE(fs::exists(dry_run_plant_file(dir_)));
  auto next = scu_only(setup);
  EXPECT_NEAR(next->scu()->actuator(1).position_mm(), 5.0, 0.01);
  EXPECT_TRUE(next->scu()->initialised(1)) << "a powered cell keeps its initialisation";
  EXPECT_NEAR(next->scu()->actuator(2).position_mm(), 0.0, 1e-9);
  EXPECT_FALSE(next->scu()->initialised(2));
}

TEST_F(PlantStateTest, APowerCycleKeepsTheRodsAndLosesTheInitialisation) {
  {
    auto first = scu_only(dry_run_emulator_setup(cell_, dir_));
    move(*first, 2, 12.0);
    move(*first, 2, 0.0);
    move(*first, 2, 7.5);
  }
  auto cycled = scu_only(dry_run_emulator_setup(cell_, dir_, /*power_cycle=*/true));
  EXPECT_NEAR(cycled->scu()->actuator(2).position_mm(), 7.5, 0.01);
  EXPECT_FALSE(cycled->scu()->initialised(2));
  cycled.reset();  // and so it stays for the next dry run, until homed again
  auto after = scu_only(dry_run_emulator_setup(cell_, dir_));
  EXPECT_FALSE(after->scu()->initialised(2));
}

TEST_F(PlantStateTest, WithoutAStateFileNothingIsKept) {
  const auto setup = emulation::load_emulator_setup(cell_);
  ASSERT_TRUE(setup.plant_state_file.empty());
  {
    auto first = scu_only(setup);
    move(*first, 1, 10.0);
  }
  auto next = scu_only(setup);
  EXPECT_NEAR(next->scu()->actuator(1).position_mm(), 0.0, 1e-9);
}

TEST_F(PlantStateTest, TheDryRunEncoderEepromLivesInTheStateFolderUnlessTheConfigNamesOne) {
  auto setup = dry_run_emulator_setup(cell_, dir_);
  ASSERT_TRUE(setup.encoder);
  EXPECT_EQ(setup.encoder->state_file, emulation::load_emulator_setup(cell_).encoder->state_file)
      << "config/cell.yaml names its own state_file";
  // Same cell, read from a copy without the emulator's state_file.
  fs::create_directories(dir_);
  std::ifstream in(cell_.source);
  std::ofstream out(dir_ / "cell.yaml");
  for (std::string line; std::getline(in, line);)
    if (line.find("state_file:") == std::string::npos) out << line << "\n";
  out.close();
  const auto copy = config::load_cell_config(dir_ / "cell.yaml");
  EXPECT_EQ(dry_run_emulator_setup(copy, dir_ / "state").encoder->state_file,
            dir_ / "state" / "encoder.dry-run.eeprom");
}

TEST_F(PlantStateTest, AFileThatIsNotThePlantsStateIsNamedNotTaken) {
  fs::create_directories(dir_);
  std::ofstream(dry_run_plant_file(dir_)) << "{\"scu_actuators\": [{\"actuator\": 9}]}";
  try {
    (void)load_plant_state(dry_run_plant_file(dir_));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("plant.dry-run.json: not the emulated plant's state"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cellctl::runtime
