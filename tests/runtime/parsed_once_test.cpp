// The cell config is parsed once (issue 24 item 2): the emulators' set-up and the plant link read their
// sections from the file as config/ parsed it, not from the file again — a file changed (or gone)
// after the load changes nothing — and their errors still name file:line:column.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "config/cell_config.hpp"
#include "emulation/emulator_setup.hpp"
#include "plant_link/link_config.hpp"

namespace cellctl::runtime {
namespace {

namespace fs = std::filesystem;

class ParsedOnce : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cellctl-parsed-once-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    std::ifstream in(fs::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
    std::stringstream text;
    text << in.rdbuf();
    shipped_ = text.str();
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& text) {
    std::ofstream(dir_ / "cell.yaml") << text;
    return dir_ / "cell.yaml";
  }
  // The shipped cell with its plant's encoder slip set to `slip` and a plant link on `port`.
  [[nodiscard]] std::string cell_with(const std::string& slip, const std::string& port) const {
    auto text = shipped_;
    const std::string key = "encoder_slip: 0.0";
    const auto at = text.find(key);
    EXPECT_NE(at, std::string::npos) << "config/cell.yaml has no plant encoder_slip";
    text.replace(at, key.size(), "encoder_slip: " + slip);
    return text + "\nplant_link:\n  port: " + port + "\n";
  }
  // The line of the shipped cell's plant encoder_slip, 1-based.
  [[nodiscard]] int slip_line() const {
    const auto at = shipped_.find("encoder_slip: 0.0");
    return static_cast<int>(std::count(shipped_.begin(), shipped_.begin() + static_cast<long>(at), '\n')) + 1;
  }

  fs::path dir_;
  std::string shipped_;
};

TEST_F(ParsedOnce, TheEmulatorsAndThePlantLinkReadTheFileAsItWasLoaded) {
  const auto file = write(cell_with("0.01", "18830"));
  const auto cell = config::load_cell_config(file);
  write("cell: [not, what, was, loaded\n");  // the file changed after the load: no longer even YAML
  const auto setup = emulation::load_emulator_setup(cell);
  EXPECT_DOUBLE_EQ(setup.plant.encoder_slip, 0.01);
  ASSERT_TRUE(setup.scu);
  const auto link = plant_link::load_link_config(cell.document.value(), cell);
  ASSERT_TRUE(link);
  EXPECT_EQ(link->port, 18830);
}

TEST_F(ParsedOnce, TheirErrorsStillNameFileLineAndColumn) {
  const auto file = write(cell_with("0.9", "0"));
  const auto cell = config::load_cell_config(file);  // the core and the devices are fine
  const auto lines = static_cast<int>(std::count(shipped_.begin(), shipped_.end(), '\n'));
  try {
    (void)emulation::load_emulator_setup(cell);
    ADD_FAILURE() << "a slip of 0.9 was taken";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(e.line(), slip_line());
    EXPECT_EQ(e.field(), "plant.encoder_slip");
  }
  try {
    (void)plant_link::load_link_config(cell.document.value(), cell);
    ADD_FAILURE() << "port 0 was taken";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(e.line(), lines + 3);
    EXPECT_EQ(e.field(), "plant_link.port");
  }
}

}  // namespace
}  // namespace cellctl::runtime
