// Every fuzz target's seed corpus and findings, replayed under the normal compiler and the asan
// preset's sanitizers, so CI checks them without clang or libFuzzer:
//   fuzz/corpus/<target>/*         seeds: must pass
//   fuzz/findings/<target>/*       inputs that once broke a target and were fixed: must pass
//   fuzz/findings/open/<target>/*  inputs that still break a target (an open issue; see
//                                  fuzz/findings/open/README.md): must still break it — when one
//                                  passes, the defect was fixed and the file moves to findings/.
// A target signals a broken property by aborting, so a failing input fails its test.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <vector>

#include "fuzz/targets.hpp"

namespace cellctl::fuzz {

// Test output names the target, not its bytes (found by argument-dependent lookup).
void PrintTo(const NamedTarget& target, std::ostream* os);
void PrintTo(const NamedTarget& target, std::ostream* os) {
  *os << target.name;
}

namespace {

const std::filesystem::path kFuzzDir = CELLCTL_FUZZ_DIR;

std::vector<std::uint8_t> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The files of a folder, sorted (an absent folder has none).
std::vector<std::filesystem::path> files_in(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().filename() != "README.md") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

void replay(const NamedTarget& target, const std::filesystem::path& file) {
  // On stderr before the run: when the target aborts, the test's output names the input.
  std::fprintf(stderr, "replaying %s\n", file.c_str());
  const auto bytes = read_bytes(file);
  target.run(bytes);
}

class Replay : public ::testing::TestWithParam<NamedTarget> {};

TEST_P(Replay, SeedCorpusPasses) {
  const auto seeds = files_in(kFuzzDir / "corpus" / GetParam().name);
  EXPECT_GE(seeds.size(), 2u) << "every target has a seed corpus in fuzz/corpus/" << GetParam().name;
  for (const auto& file : seeds) replay(GetParam(), file);
}

TEST_P(Replay, FixedFindingsStayFixed) {
  for (const auto& file : files_in(kFuzzDir / "findings" / GetParam().name)) replay(GetParam(), file);
}

TEST_P(Replay, OpenFindingsStillReproduce) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  for (const auto& file : files_in(kFuzzDir / "findings" / "open" / GetParam().name)) {
    const auto bytes = read_bytes(file);
    EXPECT_DEATH(GetParam().run(bytes), "fuzz property broken")
        << file << " no longer breaks " << GetParam().name
        << ": the defect is fixed. Move the file to fuzz/findings/" << GetParam().name
        << "/ and FUZZ_CHECK_OPEN to FUZZ_CHECK.";
  }
}

INSTANTIATE_TEST_SUITE_P(Fuzz, Replay, ::testing::ValuesIn(kTargets),
                         [](const auto& p) { return std::string(p.param.name); });

// A folder under fuzz/corpus or fuzz/findings that names no target would never be replayed.
TEST(ReplayFolders, NameATarget) {
  const auto known = [](const std::string& name) {
    for (const auto& t : kTargets)
      if (t.name == name) return true;
    return false;
  };
  for (const auto* sub : {"corpus", "findings", "findings/open"}) {
    const auto dir = kFuzzDir / sub;
    if (!std::filesystem::is_directory(dir)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (!entry.is_directory() || entry.path().filename() == "open") continue;
      EXPECT_TRUE(known(entry.path().filename().string())) << entry.path() << " names no fuzz target";
    }
  }
}

}  // namespace
}  // namespace cellctl::fuzz
