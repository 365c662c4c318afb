#pragma once
// The job scheduler of a standing controller (`cellctl serve`): while the plant link and the operator
// page stay up (their RunAccess is access()), the jobs they start run one at a time on the serving
// thread — a recipe from the recipe folder, homing (the one-step recipe `cellctl home` runs) or a
// Teach-In whose verified result is written into the cell config (as `cellctl teach-in` writes it,
// after which the config is read again). Each job gets its own run record under the runs folder.
//
// Whether a command or a start is taken is the arbiter's to decide (command/arbiter.hpp: age, PackML
// interlocks — a start only in Idle, so after a job's Complete or Stopped a Reset, after Aborted a
// Clear and a Reset); the scheduler is the arbiter's JobPort for the job in progress. A start is never
// taken after a job left a device's safe state unknown (a spindle that may still turn) or the
// encoder's parameters unconfirmed: someone must look at the cell and start cellctl again. Commands go
// to the job in progress: a recipe's or homing's run takes them as the terminal's (its journaled
// outcome is the answer); a Teach-In takes stop and abort (it aborts and restores the encoder's
// parameters) and refuses the others. A stop or abort while a job starts is never refused: a job not
// yet taken is cancelled (told as Stopped or Aborted, nothing moved), one being set up is stopped
// before any motion.
//
// Between jobs the scheduler itself tells the link and the page what it and the arbiter did (a job that
// could not start, a reset) as the run's events would: the jobs' journal threads and the scheduler never
// tell at the same time (a job's journal joins its writer before its run returns, and what the arbiter
// says during a job goes into that job's journal), so the listener hears one teller at a time.

#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>

#include "command/arbiter.hpp"
#include "config/cell_config.hpp"
#include "jobs/end_state_gate.hpp"
#include "journal/event_listener.hpp"
#include "plant_link/run_access.hpp"
#include "runtime/cell_links.hpp"
#include "runtime/cell_run.hpp"
#include "status/status_view.hpp"

namespace cellctl::jobs {

struct SchedulerOptions {
  runtime::RunMode mode = runtime::RunMode::emulated;
  std::filesystem::path config_file;        // read again after a Teach-In wrote it
  std::filesystem::path runs_dir = "runs";  // each job's record: <runs>/<job>-<time>
  std::filesystem::path state_dir;          // the home record's folder; empty: the config's
  bool trace = false;
  std::vector<runtime::FaultSpec> faults;  // rehearsed in every job (dry runs only)
  std::chrono::milliseconds max_command_age = command::kDefaultMaxCommandAge;
};

class JobScheduler {
 public:
  JobScheduler(config::CellConfig cell, SchedulerOptions options);
  JobScheduler(const JobScheduler&) = delete;
  JobScheduler& operator=(const JobScheduler&) = delete;

  // For the plant link and the operator page; valid as long as the scheduler.
  [[nodiscard]] plant_link::RunAccess access();
  [[nodiscard]] command::Arbiter& arbiter() noexcept { return arbiter_; }
  // Every event of every job, and the scheduler's own; set before serve(), outliving it.
  void listen(journal::EventListener* listener) { listener_ = listener; }

  // Reads the cell once, before any job and before serve() (runtime/cell_look.hpp: nothing is
  // commanded), so that the page's axes and devices and the plant's Idle status show it from the
  // start; says what it read, or why it could not (serve stands by all the same). serve() tells the
  // listener the sample it read first, as a job's run tells its own.
  void look(const std::function<void(const std::string&)>& say);

  // Runs the jobs as they are started, saying each one's start and end through `say`, until
  // `terminate` (a job in progress gets its controlled stop first) or an `interrupt` while no job is
  // in progress; an interrupt during a job is that job's Ctrl-C. A job started but not yet taken then
  // never starts (told as not started). Returns the exit status (exit_codes/exit_codes.hpp): ended by
  // SIGTERM, by Ctrl-C, or a job left a device's safe state unknown or the encoder's parameters
  // unconfirmed.
  int serve(std::atomic<bool>& interrupt, std::atomic<bool>& terminate,
            const std::function<void(const std::string&)>& say);

  // Jobs started and ended so far (for tests and the final line).
  [[nodiscard]] int jobs_done() const noexcept { return jobs_done_.load(); }

 private:
  enum class Busy { none, starting, run, ending };
  // Clears the job's run pointers when its run returns or throws.
  struct JobSlot;

  // What a job came to: its words for `say`, and the state the cell is left in.
  struct JobEnd {
    std::string words;
    supervisor::State state = supervisor::State::aborted;
    // The run's end state (its journal's), told only once the job's work is saved and the scheduler is
    // free for the command the plant sends on it (a reset on Complete).
    std::optional<HeldEndState> end_state;
  };

  // The arbiter's port to the job in progress.
  [[nodiscard]] supervisor::State job_state();
  [[nodiscard]] plant_link::Taken request(supervisor::Command c, const command::CommandSource& source);
  [[nodiscard]] std::optional<plant_link::LiveRun> status();
  // Registers a start the arbiter allowed.
  [[nodiscard]] plant_link::Taken start(const plant_link::StartRequest& r, const command::CommandSource& by);
  // The job, on the serving thread.
  JobEnd run_job(const plant_link::StartRequest& r, std::atomic<bool>& interrupt,
                 std::atomic<bool>& terminate);
  // Every job — a recipe, a homing, a Teach-In — is a run of runtime::CellRun. `after` adds what the
  // job does once its run has ended (a Teach-In writes what it taught) to its end.
  using AfterRun = std::function<void(const runtime::RunResult&, JobEnd&)>;
  JobEnd run_recipe(const recipe::Recipe& recipe, const std::filesystem::path& run_dir,
                    std::atomic<bool>& interrupt, std::atomic<bool>& terminate, const AfterRun& after = {});
  // A verified Teach-In's result into the config (a dry run's copy in a dry run), and the config
  // loaded again for the next jobs; one whose encoder was not restored blocks further starts.
  void after_teach_in(const runtime::RunResult& r, bool manual, JobEnd& end);
  // <runs>/<stem>-<local time>-job<N>: the next job's record.
  [[nodiscard]] std::filesystem::path job_dir(const std::string& stem) const;
  // An event of the scheduler's own (between jobs: the jobs' journal threads are not telling).
  void tell_event(const journal::Event& e) const;
  void tell_note(std::string_view words) const;
  // A job that could not start, told as a run of its own that ends in `end` (Aborted: it failed;
  // Stopped or Aborted: a stop or an abort cancelled it) with the reason.
  JobEnd not_started(const plant_link::StartRequest& r, const std::string& why,
                     supervisor::State end = supervisor::State::aborted) const;
  // The arbiter's own words (between jobs), as the run's events.
  [[nodiscard]] command::Tell arbiter_tell();

  config::CellConfig cell_;
  SchedulerOptions options_;
  journal::EventListener* listener_ = nullptr;

  std::mutex mutex_;  // everything below, between the serving thread and the link's and page's
  std::condition_variable started_;
  Busy busy_ = Busy::none;
  std::string job_;                                  // what is in progress, in words
  std::optional<plant_link::StartRequest> pending_;  // started, not yet taken by the serving thread
  std::string started_by_;                           // who started the last job (CommandSource::words())
  runtime::CellRun* run_ = nullptr;                  // the job's run in progress
  std::optional<supervisor::Command> early_stop_;    // a stop or abort while the job was set up
  std::optional<supervisor::Command> cancelled_;     // a stop or abort before the job was taken
  std::string blocked_;                              // why no start is taken any more
  std::optional<status::StatusView> at_rest_;        // the cell as look() read it
  std::optional<journal::Sample> rest_sample_;       // the same, as the journal samples it
  std::atomic<int> jobs_done_{0};
  command::Arbiter arbiter_;  // last: its Tell reaches the members above
};

}  // namespace cellctl::jobs
