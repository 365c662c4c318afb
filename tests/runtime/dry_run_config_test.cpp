// A dry run's config change goes to a copy (issue 22, item 1): config::change_config_copy reads the
// cell's config, writes the changed text to the dry-run file, and leaves the cell's config byte for byte.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/cell_config.hpp"
#include "config/config_edit.hpp"
#include "runtime/dry_run_state.hpp"

namespace cellctl::runtime {
namespace {

namespace fs = std::filesystem;

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(DryRunConfig, TheChangeGoesToTheCopyAndTheCellsConfigStaysAsItWas) {
  const auto dir = fs::temp_directory_path() / "cellctl-dry-run-config";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto config = dir / "cell.yaml";
  fs::copy_file(fs::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml", config);
  const auto before = bytes_of(config);

  const auto copy = dry_run_config_file(dir / "state");
  const auto change = config::change_config_copy(config, copy, "encoder", {{"preset_offset", "1234"}});

  EXPECT_EQ(bytes_of(config), before);
  EXPECT_FALSE(fs::exists(dir / "cell.yaml.bak"));
  EXPECT_TRUE(change.backup.empty());
  ASSERT_EQ(change.changed.size(), 1u);
  EXPECT_NE(change.changed[0].find("encoder.preset_offset: (none) → 1234"), std::string::npos);
  EXPECT_EQ(config::load_cell_config(copy).encoder->session.expected_offset, 1234);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cellctl::runtime
