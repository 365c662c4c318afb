// The page's run history: each run record in the folder, newest first, with its recipe, outcome,
// duration, each device's safe state (by the names the summary gives) and its plot; a run without a
// summary is unfinished; what is no plain run name is never read; a report for a name that is a path
// is refused.
#include "web/run_history.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace cellctl::web {
namespace {

namespace fs = std::filesystem;

// The history as the page is sent it.
nlohmann::json history(const fs::path& dir) {
  return nlohmann::json::parse(schema::run_history_json(run_history(dir)));
}

class RunsFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cellctl-run-history-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A record whose journal was last written `age` ago.
  void record(const std::string& name, const std::string& lines, std::chrono::seconds age) {
    fs::create_directories(dir_ / name);
    std::ofstream(dir_ / name / "journal.jsonl") << lines;
    fs::last_write_time(dir_ / name / "journal.jsonl", fs::file_time_type::clock::now() - age);
  }
  fs::path dir_;
};

const std::string kHeader = R"({"event":"record","recipe":"short-compare","cell":"demo-cell"})"
                            "\n"
                            R"({"event":"state","t":0.0})"
                            "\n";

TEST_F(RunsFolder, NewestFirstWithOutcomeDurationSafeStatesAndPlot) {
  record(
      "short-1-job1",
      kHeader +
          R"({"event":"summary","outcome":"complete","duration_s":5.5,"devices":)"
          R"({"dio":{"safe":"bounded","evidence":"relays off"},"scu":{"safe":"observed","evidence":"at rest"}}})"
          "\n",
      std::chrono::seconds(100));
  std::ofstream(dir_ / "short-1-job1" / "plot.html") << "<html></html>";
  record("home-2-job2", kHeader, std::chrono::seconds(10));  // still being written
  fs::create_directories(dir_ / "not-a-record");
  const auto h = history(dir_);
  ASSERT_EQ(h["runs"].size(), 2u) << h.dump();
  const auto& newest = h["runs"][0];
  EXPECT_EQ(newest["run"], "home-2-job2");
  EXPECT_TRUE(newest["outcome"].is_null());
  EXPECT_FALSE(newest["plot"].get<bool>());
  const auto& done = h["runs"][1];
  EXPECT_EQ(done["recipe"], "short-compare");
  EXPECT_EQ(done["outcome"], "complete");
  EXPECT_DOUBLE_EQ(done["duration_s"].get<double>(), 5.5);
  EXPECT_TRUE(done["plot"].get<bool>());
  ASSERT_EQ(done["devices"].size(), 2u);
  EXPECT_EQ(done["devices"][0],
            (nlohmann::json{{"name", "dio"}, {"safe", "bounded"}, {"evidence", "relays off"}}));
}

TEST_F(RunsFolder, ALastLineLongerThanTheBoundIsNotReadAsTheSummary) {
  record("long-job1",
         kHeader + R"({"event":"summary","outcome":"complete","pad":")" + std::string(kMaxRecordLine, 'x') +
             "\"}\n",
         std::chrono::seconds(1));
  const auto h = history(dir_);
  ASSERT_EQ(h["runs"].size(), 1u);
  EXPECT_TRUE(h["runs"][0]["outcome"].is_null());
  EXPECT_EQ(h["runs"][0]["recipe"], "short-compare");
}

TEST_F(RunsFolder, LinesOfAnotherShapeReadAsNoneAndNeverStopTheListing) {
  // Keys of other types than this version writes (the old reader threw on the first two).
  record("odd-job1",
         R"({"event":7,"recipe":"x"})"
         "\n"
         R"({"event":"summary","outcome":3,"devices":{"scu":"observed"}})"
         "\n",
         std::chrono::seconds(1));
  record("other-job2", "not json\n[1,2]\n", std::chrono::seconds(2));
  const auto h = history(dir_);
  ASSERT_EQ(h["runs"].size(), 2u) << h.dump();
  for (const auto& run : h["runs"]) {
    EXPECT_FALSE(run.contains("recipe")) << run.dump();
    EXPECT_TRUE(run["outcome"].is_null()) << run.dump();
  }
}

TEST_F(RunsFolder, OnlyPlainNamesAreRunsAndAReportNeverFollowsAPath) {
  EXPECT_TRUE(plain_run_name("short-20261128-050327-job3"));
  for (const auto* bad : {"", ".", "..", "../etc", "a/b", ".hidden", "a b", "x\\y"})
    EXPECT_FALSE(plain_run_name(bad)) << bad;
  EXPECT_FALSE(plain_run_name(std::string(129, 'a')));
  fs::create_directories(dir_ / "inner");
  record("inner/deep", kHeader, std::chrono::seconds(1));
  EXPECT_FALSE(run_report(dir_, "inner/deep"));
  EXPECT_FALSE(run_report(dir_, "missing"));
  EXPECT_FALSE(run_report({}, "inner"));
  EXPECT_TRUE(history({})["runs"].empty()) << "a page without a runs folder lists none";
}

}  // namespace
}  // namespace cellctl::web
