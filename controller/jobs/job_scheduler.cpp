#include "jobs/job_scheduler.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <memory>

#include "device_seam/device_registry.hpp"
#include "exit_codes/exit_codes.hpp"
#include "jobs/end_state_gate.hpp"
#include "jobs/home_job.hpp"
#include "jobs/run_record_info.hpp"
#include "jobs/teach_in_job.hpp"
#include "journal/record_header.hpp"
#include "recipe/program.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/cell_look.hpp"
#include "runtime/dry_run_state.hpp"

namespace cellctl::jobs {
namespace {

using namespace std::chrono_literals;
using plant_link::Taken;

// What a start is, in words.
std::string describe(const plant_link::StartRequest& r) {
  if (const auto* recipe = std::get_if<plant_link::StartRecipe>(&r))
    return fmt::format("recipe '{}' ({} step{})", recipe->name, recipe->steps, recipe->steps == 1 ? "" : "s");
  if (const auto* home = std::get_if<plant_link::StartHoming>(&r))
    return home->axes.empty() ? std::string("homing of every axis with homing")
                              : fmt::format("homing of {}", fmt::join(home->axes, ", "));
  const auto& t = std::get<plant_link::StartTeachIn>(r);
  return fmt::format("Teach-In of the encoder on axis {} over {:g} mm", t.axis, t.distance_mm);
}

// The job's name in the mode tag ("recipe"): the recipe's, "home", "teach-in x".
std::string short_name(const plant_link::StartRequest& r) {
  if (const auto* recipe = std::get_if<plant_link::StartRecipe>(&r)) return recipe->name;
  if (std::holds_alternative<plant_link::StartHoming>(r)) return "home";
  return "teach-in " + std::get<plant_link::StartTeachIn>(r).axis;
}

// What the job is for, as the plant counts it (journal::RunStarted::job).
std::string_view job_of(const plant_link::StartRequest& r) {
  if (std::holds_alternative<plant_link::StartRecipe>(r)) return "recipe";
  if (std::holds_alternative<plant_link::StartHoming>(r)) return "homing";
  return "teach-in";
}

bool is_stop(supervisor::Command c) {
  return c == supervisor::Command::stop || c == supervisor::Command::abort;
}

// A Teach-In asked from outside: moved by the SCU (no operator at the terminal to confirm a hand's
// move), verified within the command line's default tolerance.
TeachInAsk ask_of(const plant_link::StartTeachIn& t) {
  return {t.axis, t.distance_mm, t.from_mm, false, t.speed_mm_s, TeachInAsk{}.tolerance_mm};
}

}  // namespace

JobScheduler::JobScheduler(config::CellConfig cell, SchedulerOptions options)
    : cell_(std::move(cell)),
      options_(std::move(options)),
      arbiter_(options_.max_command_age, arbiter_tell()) {
  arbiter_.attach(
      {[this] { return job_state(); },
       [this](supervisor::Command c, const command::CommandSource& source) { return request(c, source); }});
}

command::Tell JobScheduler::arbiter_tell() {
  command::Tell tell;
  tell.command = [this](supervisor::Command c, const command::CommandSource& source) {
    tell_event(
        {0.0, journal::Command{supervisor::to_string(c), journal::Text::format("{}", source.words())}});
  };
  tell.state = [this](supervisor::State from, supervisor::State to, const std::string& reason) {
    tell_event({0.0, journal::StateChanged{supervisor::to_string(from), supervisor::to_string(to),
                                           journal::Text::format("{}", reason)}});
  };
  tell.note = [this](const std::string& words) {
    // During a recipe's or homing's run the note goes into its journal (one writer at a time).
    std::lock_guard lock(mutex_);
    if (busy_ == Busy::run) {
      run_->note_from_operator(words);
    } else if (busy_ == Busy::none) {
      tell_note(words);
    } else {
      spdlog::warn("{}", words);  // a Teach-In's journal, or a job between its states: the log only
    }
  };
  return tell;
}

plant_link::RunAccess JobScheduler::access() {
  plant_link::RunAccess a;
  a.arbiter = &arbiter_;
  a.status = [this] { return status(); };
  a.mode = to_string(options_.mode);
  a.at_rest = [this] {
    std::lock_guard lock(mutex_);
    return at_rest_;
  };
  a.start = [this](const plant_link::StartRequest& r, const command::CommandSource& by) {
    return start(r, by);
  };
  return a;
}

struct JobScheduler::JobSlot {
  JobScheduler& scheduler;
  ~JobSlot() {
    std::lock_guard lock(scheduler.mutex_);
    scheduler.run_ = nullptr;
    scheduler.busy_ = Busy::ending;  // no command reaches a run that is gone
  }
};

supervisor::State JobScheduler::job_state() {
  std::lock_guard lock(mutex_);
  switch (busy_) {
    case Busy::run:
      return run_->status().read().state;
    case Busy::ending:
      return supervisor::State::completing;
    case Busy::none:
    case Busy::starting:
      break;
  }
  return supervisor::State::starting;
}

Taken JobScheduler::request(supervisor::Command c, const command::CommandSource& source) {
  const auto word = supervisor::to_string(c);
  std::lock_guard lock(mutex_);
  switch (busy_) {
    case Busy::run:
      run_->request(c, source.words());
      return {Taken::How::by_run, {}};
    case Busy::none:
    case Busy::starting:
      if (!is_stop(c))
        return {Taken::How::refused, fmt::format("{} is not possible while the {} starts", word, job_)};
      if (pending_) {  // not taken by the serving thread yet: it never starts; that thread tells the end
        cancelled_ = c;
        started_.notify_all();
        return {Taken::How::done,
                fmt::format("{}: the {} is cancelled before it started; nothing moved", word, job_)};
      }
      early_stop_ = c;  // being set up: stopped as soon as its run exists, before any motion
      return {
          Taken::How::done,
          fmt::format("{}: taken while the {} starts: it is stopped before any motion; its end (the state "
                      "tag) tells the outcome",
                      word, job_)};
    case Busy::ending:
      return {Taken::How::refused, fmt::format("{} is not possible while the {} ends", word, job_)};
  }
  return {Taken::How::refused, fmt::format("{} is not possible now", word)};
}

std::optional<plant_link::LiveRun> JobScheduler::status() {
  std::lock_guard lock(mutex_);
  if (busy_ != Busy::run) return std::nullopt;
  return plant_link::live_run(run_->status());
}

Taken JobScheduler::start(const plant_link::StartRequest& r, const command::CommandSource& by) {
  std::lock_guard lock(mutex_);
  if (!blocked_.empty()) return {Taken::How::refused, blocked_};
  if (busy_ != Busy::none)  // the arbiter allows a start only in Idle: a job still ending is not Idle
    return {Taken::How::refused, fmt::format("the {} is still in progress", job_)};
  // Checked here, so that the plant hears why at once; the job itself runs on the serving thread.
  if (const auto* home = std::get_if<plant_link::StartHoming>(&r)) {
    const auto axes = homing_axes(cell_, options_.config_file, home->axes);
    if (const auto* why = std::get_if<std::string>(&axes)) return {Taken::How::refused, "home: " + *why};
  } else if (const auto* t = std::get_if<plant_link::StartTeachIn>(&r)) {
    const auto req = teach_in_request(cell_, ask_of(*t));
    if (const auto* why = std::get_if<std::string>(&req)) return {Taken::How::refused, "teach-in: " + *why};
  }
  busy_ = Busy::starting;
  job_ = describe(r);
  early_stop_.reset();
  cancelled_.reset();
  pending_ = r;
  started_by_ = by.words();
  started_.notify_all();
  return {Taken::How::done, "started: " + job_};
}

void JobScheduler::tell_event(const journal::Event& e) const {
  if (listener_) listener_->on_event(e);
}

void JobScheduler::tell_note(std::string_view words) const {
  if (listener_) listener_->on_note(0.0, words);
}

JobScheduler::JobEnd JobScheduler::not_started(const plant_link::StartRequest& r, const std::string& why,
                                               supervisor::State end) const {
  const auto to = supervisor::to_string(end);
  const auto name = short_name(r);
  tell_event({0.0, journal::RunStarted{name, {}, to_string(options_.mode), 0, job_of(r)}});
  tell_event({0.0, journal::StateChanged{"Starting", to, journal::Text::format("not started: {}", why)}});
  return {fmt::format("{}: not started: {}", to, why), end, std::nullopt};
}

void JobScheduler::look(const std::function<void(const std::string&)>& say) {
  runtime::LookOptions o;
  o.mode = options_.mode;
  o.state_dir = options_.state_dir;
  o.trace = options_.trace;
  try {
    // The dry runs' emulated plant, as the jobs find it (run_recipe).
    if (o.mode != runtime::RunMode::hardware)
      o.emulators = runtime::dry_run_emulator_setup(
          cell_, options_.state_dir.empty() ? cell_.state_dir : options_.state_dir);
    auto look = runtime::look_at_cell(cell_, std::move(o));
    say(fmt::format("  the cell as it stands: {}", look.words));
    std::lock_guard lock(mutex_);
    at_rest_ = look.view;
    rest_sample_ = look.sample;
  } catch (const std::exception& e) {
    say(fmt::format("  the cell could not be read before the first job: {}", e.what()));
  }
}

int JobScheduler::serve(std::atomic<bool>& interrupt, std::atomic<bool>& terminate,
                        const std::function<void(const std::string&)>& say) {
  if (rest_sample_) tell_event({0.0, *rest_sample_});  // the cell as look() read it: the plant's Idle status
  for (;;) {
    std::optional<plant_link::StartRequest> job;
    std::optional<supervisor::Command> cancelled;
    std::string what;
    const bool ending = [&] {
      std::unique_lock lock(mutex_);
      started_.wait_for(lock, 20ms, [&] { return pending_.has_value(); });
      if (terminate.load() || interrupt.load()) return true;  // a job not taken yet never starts
      job.swap(pending_);
      cancelled.swap(cancelled_);
      what = job_;
      return false;
    }();
    if (ending) {
      std::optional<plant_link::StartRequest> dropped;
      {
        std::lock_guard lock(mutex_);
        dropped.swap(pending_);
        busy_ = Busy::ending;
      }
      if (dropped) {
        const auto end = not_started(*dropped, "cellctl serve was ended before it started");
        arbiter_.job_ended(end.state);
        say(fmt::format("job {}: {}", jobs_done_.load() + 1, end.words));
      }
      break;
    }
    if (!job) continue;
    say(fmt::format("job {}: {} started", jobs_done_.load() + 1, what));
    const auto end = cancelled
                         ? not_started(*job,
                                       fmt::format("cancelled by a {} before it started; nothing moved",
                                                   supervisor::to_string(*cancelled)),
                                       *cancelled == supervisor::Command::abort ? supervisor::State::aborted
                                                                                : supervisor::State::stopped)
                         : run_job(*job, interrupt, terminate);
    // Told to the arbiter before the scheduler is free again: from here on the cell is in the job's end
    // state, and only a reset (a clear and a reset after Aborted) brings it back to Idle.
    arbiter_.job_ended(end.state);
    say(fmt::format("job {}: {}", ++jobs_done_, end.words));
    {
      std::lock_guard lock(mutex_);
      busy_ = Busy::none;
      job_.clear();
    }
    if (end.end_state)
      tell_event(end.end_state->event());  // the scheduler takes the plant's next command now
    interrupt.store(false);                // a Ctrl-C during the job was the job's
  }
  if (!blocked_.empty()) return kExitSafeStateUnknown;
  return terminate.load() ? kExitOk : kExitInterrupted;
}

std::filesystem::path JobScheduler::job_dir(const std::string& stem) const {
  const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  // Each job its own folder, even two in one second (a virtual-time run takes a fraction of one).
  return options_.runs_dir /
         fmt::format("{}-{:%Y%m%d-%H%M%S}-job{}", stem, fmt::localtime(now), jobs_done_.load() + 1);
}

JobScheduler::JobEnd JobScheduler::run_job(const plant_link::StartRequest& r, std::atomic<bool>& interrupt,
                                           std::atomic<bool>& terminate) {
  try {
    if (const auto* t = std::get_if<plant_link::StartTeachIn>(&r)) {
      const auto request =
          std::get<routines::TeachInRequest>(teach_in_request(cell_, ask_of(*t)));  // start() checked
      const auto dir = job_dir("teach-in-" + t->axis);
      return run_recipe(teach_in_recipe(cell_, request, dir), dir, interrupt, terminate,
                        [this, manual = request.manual](const runtime::RunResult& result, JobEnd& end) {
                          after_teach_in(result, manual, end);
                        });
    }
    if (const auto* recipe = std::get_if<plant_link::StartRecipe>(&r))
      return run_recipe(recipe::load_recipe(recipe->file, cell_), job_dir(recipe->file.stem().string()),
                        interrupt, terminate);
    // The axes were checked by start() against this same config.
    const auto axes = std::get<std::vector<std::size_t>>(
        homing_axes(cell_, options_.config_file, std::get<plant_link::StartHoming>(r).axes));
    const auto dir = job_dir("home");
    return run_recipe(write_homing_recipe(cell_, axes, dir), dir, interrupt, terminate);
  } catch (const recipe::RecipeErrors& e) {
    std::string why = fmt::format("{} problem(s)", e.errors().size());
    for (const auto& err : e.errors()) why += fmt::format("; {}", err.what());
    return not_started(r, why);
  } catch (const std::exception& e) {
    return not_started(r, e.what());  // a port that does not open, a record folder that cannot be made
  }
}

JobScheduler::JobEnd JobScheduler::run_recipe(const recipe::Recipe& recipe,
                                              const std::filesystem::path& run_dir,
                                              std::atomic<bool>& interrupt, std::atomic<bool>& terminate,
                                              const AfterRun& after) {
  runtime::RunOptions o;
  o.mode = options_.mode;
  o.journal_dir = run_dir;
  o.state_dir = options_.state_dir;
  o.trace = options_.trace;
  o.faults = options_.faults;
  {
    std::lock_guard lock(mutex_);
    o.start_source = started_by_;  // the run's start is told as the plant's or the page's
  }
  // The dry run's emulated plant kept between jobs (and serve's runs), as a powered cell keeps its own.
  if (o.mode != runtime::RunMode::hardware)
    o.emulators = runtime::dry_run_emulator_setup(
        cell_, options_.state_dir.empty() ? cell_.state_dir : options_.state_dir);
  o.record_header = journal::record_header(
      record_info(cell_, options_.config_file, recipe, recipe::unroll(recipe), o.mode));
  runtime::CellRun run(cell_, recipe, o);  // a port that does not open: thrown, reported by run_job
  EndStateGate gate(listener_);
  run.listen(&gate);
  runtime::RunResult result;
  {
    const JobSlot slot{*this};
    {
      std::lock_guard lock(mutex_);
      run_ = &run;
      busy_ = Busy::run;
      if (early_stop_) run.request(*early_stop_, "a stop while the job was set up");  // taken in Starting
    }
    result = run.run(interrupt, &terminate);
  }
  run.listen(nullptr);
  const auto head = fmt::format("{} {}", supervisor::to_string(result.final_state), run_dir.string());
  std::string words = head;
  if (!result.failure.empty()) words += "; failed step: " + result.failure;
  if (!result.ended_by.empty()) words += "; ended by: " + result.ended_by;
  for (const auto& s : result.safety)  // every device slot of the cell
    if (s && s->safe == runtime::Safe::unknown) {
      std::lock_guard lock(mutex_);
      blocked_ = fmt::format(
          "no start is taken: the {} safe state is UNKNOWN since the last job ({}); look at the cell, "
          "then start cellctl again",
          s->device, s->evidence);
      words += "; WARNING: " + blocked_;
    }
  if (!result.home_record.empty()) words += "; " + result.home_record;
  JobEnd end{words, result.final_state, std::nullopt};
  if (after) after(result, end);
  // The end state goes out once the job's work is on disk (the journal closed, the home record and a
  // taught config written) and the scheduler is free again: serve() tells it.
  end.end_state =
      gate.take(end.words.size() > head.size() + 2 ? end.words.substr(head.size() + 2) : std::string());
  return end;
}

void JobScheduler::after_teach_in(const runtime::RunResult& r, bool manual, JobEnd& end) {
  if (!r.teach_in) return;
  if (!r.teach_in->restored) {
    std::lock_guard lock(mutex_);
    blocked_ =
        "no start is taken: the encoder's configured parameters could NOT be confirmed restored after the "
        "Teach-In; check with `cellctl encoder diag`, then start cellctl again";
  }
  const auto record =
      record_teach_in(options_.config_file, cell_, r, options_.mode, options_.state_dir, manual);
  end.words += "; " + record.words;
  if (record.write_failed) end.state = supervisor::State::aborted;
  if (!record.written || record.file != options_.config_file) return;
  try {
    auto fresh = device_seam::load_cell_config(options_.config_file);
    std::lock_guard lock(mutex_);
    cell_ = std::move(fresh);  // the next jobs count in what was taught
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    blocked_ = fmt::format("no start is taken: {} was written by the Teach-In but does not load again: {}",
                           options_.config_file.string(), e.what());
    end.words += "; " + blocked_;
  }
}

}  // namespace cellctl::jobs
