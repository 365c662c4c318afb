// Issue 22 item 9: every path in a cell config is relative to the config file, wherever cellctl runs
// from, so the example plant-link section works where it is pasted (config/cell.yaml).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "config/cell_config.hpp"
#include "plant_link/link_config.hpp"

namespace cellctl::config {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

// A scratch folder laid out as the repository: <dir>/config/cell.yaml, <dir>/recipes/; the test runs
// from elsewhere (the working directory is not the config's folder).
class ConfigPaths : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cellctl-config-paths-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "recipes");
    fs::create_directories(dir_ / "elsewhere");
    old_cwd_ = fs::current_path();
    fs::current_path(dir_ / "elsewhere");
  }
  void TearDown() override {
    fs::current_path(old_cwd_);
    fs::remove_all(dir_);
  }
  [[nodiscard]] fs::path shipped_cell_with(const std::string& more) const {
    const auto config = dir_ / "config" / "cell.yaml";
    write(config, read(fs::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml") + more);
    return config;
  }
  fs::path dir_;
  fs::path old_cwd_;
};

TEST_F(ConfigPaths, TheStateFolderIsBesideTheConfigFile) {
  const auto cell = load_cell_config(shipped_cell_with("\nstate_dir: state\n"));
  EXPECT_EQ(fs::weakly_canonical(cell.state_dir), fs::weakly_canonical(dir_ / "config" / "state"));
}

TEST_F(ConfigPaths, AnAbsolutePathIsTakenAsWritten) {
  const auto cell = load_cell_config(shipped_cell_with("\nstate_dir: /var/lib/cellctl\n"));
  EXPECT_EQ(cell.state_dir, fs::path("/var/lib/cellctl"));
}

TEST_F(ConfigPaths, WithoutStateDirTheStateFolderIsInTheWorkingDirectory) {
  const auto cell = load_cell_config(shipped_cell_with(""));
  EXPECT_EQ(cell.state_dir, fs::path("state"));  // beside runs/, as documented
}

TEST_F(ConfigPaths, APublishedPortIsBesideTheConfigFile) {
  auto text = read(fs::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
  const std::string shipped_port = "\nscu:\n  port: emulated\n";
  const auto at = text.find(shipped_port);
  ASSERT_NE(at, std::string::npos)
      << "config/cell.yaml: its scu section no longer starts with port: emulated";
  text.replace(at, shipped_port.size(), "\nscu:\n  port: links/scu\n  publish_as: links/scu\n");
  const auto config = dir_ / "config" / "cell.yaml";
  write(config, text);
  const auto cell = load_cell_config(config);
  ASSERT_TRUE(cell.scu);
  EXPECT_EQ(fs::path(cell.scu->port.port), dir_ / "config" / "links/scu");
  EXPECT_EQ(fs::path(cell.scu->port.publish_as), dir_ / "config" / "links/scu");
}

TEST_F(ConfigPaths, TheExamplePlantLinkSectionWorksPastedIntoTheShippedCell) {
  // As a user pastes it: the whole example file's section, its password file made to exist.
  auto section = read(fs::path(CELLCTL_SOURCE_DIR) / "config/examples/plant-link.yaml");
  const auto password = dir_ / "mqtt.password";
  write(password, "secret\n");
  const std::string key = "password_file: ";
  const auto at = section.find(key) + key.size();
  ASSERT_GT(at, key.size());
  section.replace(at, section.find(' ', at) - at, password.string());
  write(dir_ / "recipes" / "demo.yaml", "recipe: {}\n");
  const auto cell = load_cell_config(shipped_cell_with("\n" + section));
  const auto link = plant_link::load_link_config(cell.document.value(), cell);
  ASSERT_TRUE(link);
  EXPECT_TRUE(fs::is_directory(link->recipes)) << link->recipes;
  EXPECT_EQ(fs::weakly_canonical(link->recipes), fs::weakly_canonical(dir_ / "recipes"));
}

}  // namespace
}  // namespace cellctl::config
