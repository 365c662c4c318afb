#pragma once
// The controller standing by between jobs (`cellctl serve`): the plant link and the operator page
// stay up (their RunAccess is access()), and the jobs they start run one at a time on the serving
// thread — a recipe from the recipe folder, homing (the one-step recipe `cellctl home` runs) or a
// Teach-In whose verified result is written into the cell config (as `cellctl teach-in` writes it,
// after which the config is read again). Each job gets its own run record under the runs folder.
//
// A start is taken only when no job is in progress, and never after a job left a device's safe
// state unknown (a spindle that may still turn) or the encoder's parameters unconfirmed: someone must
// look at the cell and start cellctl again. Commands go to the job in progress: a recipe's or
// homing's run takes them as the terminal's (its journaled outcome is the answer); a Teach-In takes
// stop and abort (it aborts and restores the encoder's parameters) and refuses the others. A stop or
// abort while a job starts is never refused: a job not yet taken is cancelled, one being set up is
// stopped before any motion.
//
// Between jobs the standby itself tells the link and the page what it did (a Teach-In's start and
// end, a job that could not start) as journal lines: the jobs' journal threads and the standby never
// write at the same time (a job's journal joins its writer before its run returns), so the listener
// keeps one writer at a time.

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "config/cell_config.hpp"
#include "plant_link/run_access.hpp"
#include "runtime/cell_links.hpp"
#include "runtime/cell_run.hpp"

namespace cellctl::cli {

struct StandbyOptions {
  runtime::RunMode mode = runtime::RunMode::emulated;
  std::filesystem::path config_file;        // read again after a Teach-In wrote it
  std::filesystem::path runs_dir = "runs";  // each job's record: <runs>/<job>-<time>
  std::filesystem::path state_dir;          // the home record's folder; empty: the config's
  bool trace = false;
};

class CellStandby {
 public:
  CellStandby(config::CellConfig cell, StandbyOptions options);

  // For the plant link and the operator page; valid as long as the standby.
  [[nodiscard]] plant_link::RunAccess access();
  // Every journal line of every job, and the standby's own lines; set before serve().
  void on_journal_line(std::function<void(const nlohmann::json&)> listener) {
    listener_ = std::move(listener);
  }

  // Runs the jobs as they are started, saying each one's start and end through `say`, until
  // `terminate` (a job in progress gets its controlled stop first) or an `interrupt` while no job is
  // in progress; an interrupt during a job is that job's Ctrl-C. A job started but not yet taken then
  // never starts (told as not started). Returns the exit status: 0 ended by SIGTERM, 130 by Ctrl-C,
  // 5 when a job left a device's safe state unknown or the encoder's parameters unconfirmed.
  int serve(std::atomic<bool>& interrupt, std::atomic<bool>& terminate,
            const std::function<void(const std::string&)>& say);

  // Jobs started and ended so far (for tests and the final line).
  [[nodiscard]] int jobs_done() const noexcept { return jobs_done_.load(); }

 private:
  enum class Busy { none, starting, run, teach_in, ending };
  // Clears the job's run pointers when its run returns or throws.
  struct JobSlot;

  [[nodiscard]] plant_link::Taken request(supervisor::Command c);
  [[nodiscard]] std::optional<plant_link::LiveRun> status();
  [[nodiscard]] plant_link::Taken start(const plant_link::StartRequest& r);
  // The job, on the serving thread; its words for `say`.
  std::string run_job(const plant_link::StartRequest& r, std::atomic<bool>& interrupt,
                      std::atomic<bool>& terminate);
  std::string run_recipe(const recipe::Recipe& recipe, const std::filesystem::path& run_dir,
                         std::atomic<bool>& interrupt, std::atomic<bool>& terminate);
  std::string run_teach_in(const plant_link::StartTeachIn& t, std::atomic<bool>& interrupt,
                           const std::atomic<bool>& terminate);
  // <runs>/<stem>-<local time>-job<N>: the next job's record.
  [[nodiscard]] std::filesystem::path job_dir(const std::string& stem) const;
  // A line of the standby's own (between jobs: the jobs' journal threads are not writing).
  void tell(nlohmann::json line) const;
  // A job that could not start, told as a run of its own that ends Aborted with the reason.
  std::string not_started(const plant_link::StartRequest& r, const std::string& why) const;

  config::CellConfig cell_;
  StandbyOptions options_;
  std::function<void(const nlohmann::json&)> listener_;

  std::mutex mutex_;  // everything below, between the serving thread and the link's and page's
  std::condition_variable started_;
  Busy busy_ = Busy::none;
  std::string job_;                                  // what is in progress, in words
  std::optional<plant_link::StartRequest> pending_;  // started, not yet taken by the serving thread
  runtime::CellRun* run_ = nullptr;                  // the recipe's or homing's run in progress
  std::atomic<bool>* teach_abort_ = nullptr;         // the Teach-In's abort, while one runs
  std::optional<supervisor::Command> early_stop_;    // a stop or abort while the job was set up
  std::string blocked_;                              // why no start is taken any more
  std::atomic<int> jobs_done_{0};
};

}  // namespace cellctl::cli
