#include "runtime/cell_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "loop/control_stages.hpp"
#include "loop/realtime_setup.hpp"
#include "runtime/cell_view.hpp"
#include "runtime/home_record_file.hpp"

namespace cellctl::runtime {
namespace {

using loop::ControlStage;
using loop::index;

link::Duration period_of(const config::CellConfig& cell) {
  return link::milliseconds(cell.loop.period_ms);
}

supervisor::SupervisorSettings settings_for(const config::CellConfig& cell, const RunOptions& o) {
  auto s = o.supervisor;
  s.mode = to_string(o.mode);
  s.sample_s = cell.loop.sample_ms / 1000.0;
  return s;
}

// How each device's link did, from its session's health: the worst round trip and the longest
// silence between good replies say how close the run came to a link fault (an emulated run
// beside a load shows whether the emulators kept up).
std::string link_figures(const CellDevices& devices, std::vector<schema::LinkFigures>& out) {
  std::string text;
  for (const auto* d : devices.devices()) {
    const std::string name(d->name());
    const link::LinkHealth& h = d->session().health();
    const double round_trip_ms = link::to_milliseconds(h.max_round_trip);
    const double silence_ms = link::to_milliseconds(h.max_silence);
    out.push_back({name, h.good_replies, round_trip_ms, silence_ms, h.timeouts, h.retries, h.bad_frames});
    text += fmt::format(
        "link {:<8} {} replies, worst round trip {:.1f} ms, longest silence {:.1f} ms, {} time-outs, {} "
        "retries, {} bad frames\n",
        name, h.good_replies, round_trip_ms, silence_ms, h.timeouts, h.retries, h.bad_frames);
  }
  return text;
}

}  // namespace

CellRun::CellRun(const config::CellConfig& cell, const recipe::Recipe& recipe, RunOptions options)
    : cell_(cell),
      recipe_(recipe),
      program_(recipe::unroll(recipe)),
      options_(std::move(options)),
      clock_(run_clock(options_.mode, real_clock_, virtual_clock_)),
      journal_(options_.journal_dir, when_writer_full(options_.mode), options_.record_header),
      monitor_(cell) {
  home_record_file_ = runtime::home_record_path(
      options_.state_dir.empty() ? cell.state_dir : options_.state_dir,
      options_.mode == RunMode::hardware ? std::string_view{} : std::string_view{to_string(options_.mode)});
  home_record_ =
      runtime::load_home_record(home_record_file_, cell, config_sha256(cell), &home_record_problem_);
  options_.supervisor.home_record = &home_record_;
  try {
    parts_ = open_cell_parts(cell, options_.mode, clock_, virtual_clock_, options_.trace, options_.faults,
                             options_.emulators, options_.device_kinds);
    const bool teaches =
        std::any_of(program_.instructions.begin(), program_.instructions.end(),
                    [](const auto& i) { return std::holds_alternative<recipe::TeachIn>(i.action); });
    if (teaches) {
      if (!cell.encoder || !parts_.devices->encoder())
        throw std::invalid_argument("the cell has no encoder: section: nothing to teach");
      teach_in_encoder_ = std::make_unique<TeachInEncoder>(*parts_.devices->encoder(), cell.encoder->session);
      options_.supervisor.teach_in_port = teach_in_encoder_.get();
    }
  } catch (const std::exception& e) {
    // A port that did not open (or a device set-up refused): the record says why nothing ran.
    journal_.close_not_started(e.what());
    throw;
  }
  supervisor_ = std::make_unique<supervisor::Supervisor>(
      cell, recipe, program_, journal_, cell.loop.period_ms / 1000.0, settings_for(cell, options_));
  loop_ = std::make_unique<loop::Loop>(clock_, *parts_.waiter, period_of(cell), loop::kControlStages,
                                       &real_clock_);
  state_.axis_count = static_cast<std::uint8_t>(cell.axes.size());
}

CellRun::~CellRun() {
  emulators_stop_.store(true);
  if (emulator_thread_.joinable()) emulator_thread_.join();
}

void CellRun::run_emulator_thread() {
  serve_emulators(emulators_stop_, real_clock_, parts_.rehearsal.get(), *parts_.emulated);
}

void CellRun::request(supervisor::Command c, std::string_view source) noexcept {
  {
    const std::lock_guard lock(request_mutex_);
    (void)request_sources_.push({c, journal::Text::format("{}", source)});  // full: the bit still goes
  }
  requested_.fetch_or(bit(c));  // after the source: the loop that sees the bit finds its source
}

void CellRun::take_commands(double t, std::atomic<bool>& interrupt) {
  if (interrupt.exchange(false)) {
    interrupted_ = true;
    if (operator_stop_) emergency_stop_ = true;
    operator_stop_ = true;
  }
  // SIGTERM is a state, not an event: left set, so that whoever started the run (cellctl serve) ends too.
  if (terminate_ && !terminated_ && terminate_->load()) {
    terminated_ = true;
    interrupted_ = true;
    request(supervisor::Command::stop, "signal SIGTERM");  // a controlled stop, whatever stops.operator says
  }
  while (const auto note = operator_notes_.pop()) journal_.post(t, *note);
  const unsigned pending = requested_.exchange(0);
  if (pending == 0) return;
  for (auto& s : sources_) s = journal::Text::format("unrecorded");
  while (const auto r = request_sources_.pop()) sources_[static_cast<std::size_t>(r->command)] = r->source;
  // Strongest first, so that a stop typed right after a hold is never lost behind it.
  using supervisor::Command;
  for (const auto cmd : {Command::abort, Command::stop, Command::hold, Command::clear, Command::reset,
                         Command::unhold, Command::start}) {
    if ((pending & bit(cmd)) == 0) continue;
    const auto& source = sources_[static_cast<std::size_t>(cmd)];
    if (cmd == Command::reset || cmd == Command::clear) {
      judge_reset(t, cmd, source);
      continue;
    }
    if (!supervisor_->command(cmd, source.view(), t)) journal_.post(t, journal::Note{supervisor_->refusal()});
  }
}

void CellRun::judge_reset(double t, supervisor::Command c, const journal::Text& source) {
  // Judged by the interlocks first: a reset in Aborted is refused before it clears anything.
  if (const auto why = supervisor::refusal(supervisor_->state(), c); !why.empty()) {
    journal_.post(
        t, journal::Note{journal::Text::format("{} is not possible in state {}: {}", supervisor::to_string(c),
                                               supervisor::to_string(supervisor_->state()), why)});
    return;
  }
  // The devices are told to clear their own latched faults (the converter's CMD System Reset) and
  // the monitor judges its latches now: a converter fault is gone by the operator's next reset.
  supervisor_->reset_devices();
  const bool had_stop = operator_stop_ || emergency_stop_;
  operator_stop_ = emergency_stop_ = false;
  std::bitset<monitor::kRuleCount> latched;
  for (std::size_t r = 0; r < monitor::kRuleCount; ++r)
    latched[r] = monitor_.latch(static_cast<monitor::Rule>(r)).active;
  const bool clear = monitor_.reset(state_, {});
  for (std::size_t r = 0; r < monitor::kRuleCount; ++r)
    if (latched[r] && !monitor_.latch(static_cast<monitor::Rule>(r)).active)
      journal_.post(t, journal::FaultCleared{monitor::to_string(static_cast<monitor::Rule>(r))});
  if (!clear) {
    std::string_view still = "?";
    for (std::size_t r = 0; r < monitor::kRuleCount && still == "?"; ++r)
      if (monitor_.latch(static_cast<monitor::Rule>(r)).active)
        still = monitor::to_string(static_cast<monitor::Rule>(r));
    journal_.post(t, journal::Note{journal::Text::format("{} refused: the cause of {} is still present",
                                                         supervisor::to_string(c), still)});
    if (had_stop) operator_stop_ = true;
    return;
  }
  // Every latch cleared: what ends the run from here on is a fault after this reset, not the one
  // that was reset (the summary's ended_by).
  first_fault_.reset();
  // Held by a category-2 stop, the run goes on: a reset clears the latches, unhold resumes. Only a
  // run that has ended changes state.
  if (!supervisor::is_final(supervisor_->state())) {
    journal_.post(
        t, journal::Note{journal::Text::format("faults reset in state {}", to_string(supervisor_->state()))});
    return;
  }
  if (!supervisor_->command(c, source.view(), t)) journal_.post(t, journal::Note{supervisor_->refusal()});
}

void CellRun::report_devices(double t, RunResult& r) {
  // What the sessions know that the cell state could not carry (it holds no text): after the loop,
  // so composing it allocates nowhere near the cycle.
  const auto note = [&](std::string text) {
    journal::post_note(journal_, t, text);  // never cut
    r.device_notes.push_back(std::move(text));
  };
  std::vector<std::string> notes;
  for (const auto* d : parts_.devices->devices()) d->notes(notes);
  for (auto& n : notes) note(std::move(n));
}

CellRun::FirstFault CellRun::first_fault(monitor::Rule rule, config::StopCategory category, double t,
                                         const journal::Text& detail) const noexcept {
  FirstFault f{rule, category, t, detail, std::nullopt, 0.0};
  // The link that failed: of the lost or silent ones, the longest silent; the encoder when it left
  // data exchange.
  link::Duration longest{};
  const auto limit = std::chrono::duration<double, std::milli>(cell_.limits.link_silence_ms);
  for (const auto* device : parts_.devices->devices()) {
    const auto d = device->slot();
    const auto& l = state_.links[d];
    const bool failed = l.fault || !l.active || l.silent_for > limit ||
                        (d == cell::slot(cell::Device::encoder) && !state_.encoder.data_exchange);
    if (!failed || (f.link && l.silent_for <= longest)) continue;
    f.link = d;
    longest = l.silent_for;
  }
  if (f.link) f.link_since = t - link::to_seconds(longest);
  return f;
}

void CellRun::report_safety(RunResult& r, schema::RunFigures& figures) const {
  r.safety = safe_stop_->verdicts();
  for (const auto* d : parts_.devices->devices()) {
    const auto& verdict = r.safety[d->slot()];
    figures.devices.push_back({std::string(d->name()), to_string(verdict->safe), verdict->evidence});
  }
  if (!first_fault_ || supervisor_->state() == supervisor::State::complete) return;
  // A link that failed is named as the link (device, symptom, since when), whatever rule latched.
  const auto& f = *first_fault_;
  schema::EndedBy ended;
  ended.t = f.t;
  ended.rule = monitor::to_string(f.rule);
  if (f.link) {
    // The session's own words when it gave up on the link; else what the monitor saw of it.
    const auto reason = safe_stop_->lost_reason(*f.link);
    std::string symptom = reason.empty() ? std::string(f.detail.view()) : reason;
    if (auto* enc = parts_.devices->encoder();
        *f.link == cell::slot(cell::Device::encoder) && enc && !enc->restart_reason().empty())
      symptom += "; DP start-up begun again: " + enc->restart_reason();
    ended.kind = schema::EndedBy::Kind::link;
    ended.device = std::string(state_.devices[*f.link]);
    ended.symptom = symptom;
    ended.since_s = f.link_since;
    r.ended_by =
        fmt::format("{} link fault, no good reply since {:.3f} s: {}", ended.device, f.link_since, symptom);
  } else {
    const bool by_operator =
        f.rule == monitor::Rule::operator_stop || f.rule == monitor::Rule::emergency_stop;
    ended.kind = by_operator ? schema::EndedBy::Kind::operator_stop : schema::EndedBy::Kind::monitor;
    ended.detail = std::string(f.detail.view());
    r.ended_by = fmt::format("{} at {:.3f} s: {}", monitor::to_string(f.rule), f.t, f.detail.view());
  }
  figures.ended_by = std::move(ended);
}

void CellRun::publish_status(double t) {
  status::StatusView v;
  v.t = t;
  v.state = supervisor_->state();
  v.steps = static_cast<std::uint32_t>(supervisor_->step_count());
  v.step = static_cast<std::uint32_t>(std::min(supervisor_->step_index() + 1, supervisor_->step_count()));
  if (const auto* ins = supervisor_->current()) v.label = ins->label;
  v.step_planned_s = supervisor_->step_planned_s();
  show_cell(state_, home_record_, *parts_.devices, v);
  for (std::size_t i = 0; i < state_.axis_count; ++i) {
    const auto& intent = supervisor_->intents().axes[i];
    v.target_known[i] = intent.move;
    v.target_mm[i] = intent.target_mm;
  }
  v.spindle_set_hz = supervisor_->intents().spindle.run ? supervisor_->intents().spindle.frequency_hz : 0.0;
  const auto& stats = loop_->stats();
  v.jitter_max_us = std::chrono::duration<double, std::micro>(stats.jitter.max()).count();
  v.jitter_sum_s = link::to_seconds(stats.jitter.total());
  v.overruns = stats.overrun_cycles;
  // Cumulative counts per bucket: a histogram bin counts where its upper edge lies (never under).
  std::size_t bucket = 0;
  std::uint64_t running = 0;
  for (std::size_t b = 0; b < loop::LatencyHistogram::kBins; ++b) {
    const double upper_us =
        std::chrono::duration<double, std::micro>(loop::LatencyHistogram::upper_edge(b)).count();
    while (bucket < status::kJitterBucketsUs.size() && upper_us > status::kJitterBucketsUs[bucket])
      v.jitter_le[bucket++] = running;
    running += stats.jitter.bin_count(b);
  }
  while (bucket < v.jitter_le.size()) v.jitter_le[bucket++] = running;
  // Each device's safe state as the stop resolves it (its words, the evidence, come after the loop).
  for (const auto* d : parts_.devices->devices())
    if (const auto& safe = d->resolved()) v.safe[d->slot()] = to_string(*safe);
  for (std::size_t r = 0; r < monitor::kRuleCount; ++r) {
    if (!monitor_.latch(static_cast<monitor::Rule>(r)).active) continue;
    v.fault = true;
    v.first_fault = static_cast<monitor::Rule>(r);
    break;
  }
  board_.publish(v);
}

std::string_view CellRun::first_active_detail() const noexcept {
  for (std::size_t r = 0; r < monitor::kRuleCount; ++r)
    if (const auto& latch = monitor_.latch(static_cast<monitor::Rule>(r)); latch.active)
      return latch.detail.view();
  return {};
}

void CellRun::cycle(link::TimePoint now, std::atomic<bool>& interrupt) {
  const double t = link::to_seconds(now - start_);
  if (hook_) hook_(t, *this);
  if (parts_.rehearsal) parts_.rehearsal->post_journal(now, t, journal_);
  take_commands(t, interrupt);
  if (confirm_.exchange(false)) supervisor_->confirm();
  {  // the stages, timed back to back; the last ends with this block
    auto stages = loop_->stage_sequence();
    stages.begin(index(ControlStage::read_sessions));
    if (parts_.emulated && options_.mode == RunMode::virtual_time) {
      if (parts_.rehearsal) parts_.rehearsal->drive_emulators(now, *parts_.emulated);
      parts_.emulated->poll(now);
    }
    parts_.devices->receive(now);
    if (teach_in_encoder_) teach_in_encoder_->step(now);

    stages.begin(index(ControlStage::state));
    parts_.devices->read(now, state_);
    supervisor_->adjust(state_);
    safe_stop_->observe(now, state_);

    stages.begin(index(ControlStage::monitor));
    const auto fresh =
        monitor_.evaluate(state_, {.stop = operator_stop_, .emergency_stop = emergency_stop_}, t);
    for (std::size_t r = 0; r < monitor::kRuleCount; ++r) {
      if (!fresh.test(r)) continue;
      const auto rule = static_cast<monitor::Rule>(r);
      const auto& latch = monitor_.latch(rule);
      journal_.post(t, journal::Fault{monitor::to_string(rule), static_cast<std::uint8_t>(latch.category),
                                      latch.detail});
      // The fault that ended the run: the first, unless a later one demands a stronger stop (an
      // emergency stop while held by a Ctrl-C: the run ends Aborted by it).
      const bool stronger =
          first_fault_ && static_cast<int>(latch.category) < static_cast<int>(first_fault_->category);
      if ((!first_fault_ || stronger) && !shutdown_since_)
        first_fault_ = first_fault(rule, latch.category, t, latch.detail);
    }

    stages.begin(index(ControlStage::supervisor));
    supervisor_->step(state_, monitor_.demanded_stop(), t, first_active_detail());
    const auto& sp = supervisor_->intents().spindle;
    monitor_.expect_spindle(sp.run, sp.frequency_hz);
    monitor_.expect_axes(supervisor_->intents());
    if (supervisor_->cell_up() && !monitor_.armed() && !shutdown_since_) monitor_.arm();
    if (!supervisor_->cell_up() && monitor_.armed()) monitor_.disarm();

    stages.begin(index(ControlStage::write_sessions));
    if (supervisor::is_final(supervisor_->state()) && !shutdown_since_) {
      safe_stop_->begin(now);  // axes stopped, remote mode closed, spindle stopped — and confirmed
      monitor_.disarm();       // the devices go down on purpose now
      shutdown_since_ = now;
    }
    // Lost devices: port reopened, the stop sent again until confirmed or bounded.
    const auto demanded = monitor_.demanded_stop();
    safe_stop_->step(now, demanded && *demanded != monitor::StopCategory::controlled_hold);
    if (!shutdown_since_) parts_.devices->apply(supervisor_->intents());
    parts_.devices->transmit(now);  // what this cycle decided goes out in this cycle
  }
  if (shutdown_since_ && safe_stop_->done()) loop_stop_.store(true);
  publish_status(t);
}

void CellRun::save_home_record(double t, std::int64_t unix_start, RunResult& r) {
  if (!home_record_problem_.empty())
    journal_.post(0.0, journal::Note{journal::Text::format("{}", home_record_problem_)});
  if (!home_record_.updated) return;
  for (auto& a : home_record_.axes)
    if (a.homed && a.unix_time == 0) a.unix_time = unix_start + static_cast<std::int64_t>(a.run_t);
  try {
    runtime::save_home_record(home_record_file_, home_record_, cell_);
    r.home_record = "home record written: " + home_record_file_.string();
  } catch (const std::exception& e) {
    r.home_record = std::string("home record NOT written: ") + e.what();
  }
  journal_.post(t, journal::Note{journal::Text::format("{}", r.home_record)});
}

RunResult CellRun::run(std::atomic<bool>& interrupt, std::atomic<bool>* terminate) {
  terminate_ = terminate;
  // For this run only: the thread goes back to its scheduler and CPUs at the end (serve's thread
  // waits between jobs, at normal priority).
  std::optional<loop::RealtimeScope> realtime;
  if (options_.mode != RunMode::virtual_time && cell_.loop.realtime) {
    realtime.emplace(loop::RealtimeConfig{
        .fifo_priority = cell_.loop.priority, .lock_memory = true, .cpu = cell_.loop.cpu});
    realtime_warnings_ = realtime->report().warnings();
  }
  const auto wall_start = std::chrono::steady_clock::now();
  const auto unix_start =
      std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch())
          .count();
  start_ = clock_.now();
  parts_.links->start_trace_clock(start_);
  if (parts_.rehearsal) parts_.rehearsal->start(start_, parts_.links->fault_links());
  // Started after the real-time set-up, so it inherits the loop's SCHED_FIFO priority and memory lock: an
  // emulator the load keeps off the CPU would look like a device that stops answering.
  if (parts_.emulated && options_.mode != RunMode::virtual_time)
    emulator_thread_ = std::thread([this] { run_emulator_thread(); });

  safe_stop_ = std::make_unique<SafeStop>(
      *parts_.devices,
      std::chrono::duration_cast<link::Duration>(std::chrono::duration<double>(options_.shutdown_timeout_s)),
      start_);
  parts_.devices->activate(start_);
  // In Idle: never refused.
  (void)supervisor_->command(supervisor::Command::start, options_.start_source, 0.0);
  loop_->run([this, &interrupt](link::TimePoint now, std::uint64_t) { cycle(now, interrupt); }, loop_stop_);

  emulators_stop_.store(true);
  if (emulator_thread_.joinable()) emulator_thread_.join();

  RunResult r;
  if (parts_.rehearsal) parts_.rehearsal->post_run_end(link::to_seconds(clock_.now() - start_), journal_);
  report_devices(link::to_seconds(clock_.now() - start_), r);
  save_home_record(link::to_seconds(clock_.now() - start_), unix_start, r);
  r.final_state = supervisor_->state();
  r.failure = std::string(supervisor_->failure().view());
  r.interrupted = interrupted_;
  r.duration_s = link::to_seconds(clock_.now() - start_);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r.cycles = loop_->stats().cycles;
  r.loop_summary = loop_->summary();
  schema::RunFigures figures;
  r.link_summary = link_figures(*parts_.devices, figures.links);
  figures.cycles = r.cycles;
  figures.overrun_cycles = loop_->stats().overrun_cycles;
  figures.missed_deadlines = loop_->stats().missed_deadlines;
  figures.jitter_p99_us =
      std::chrono::duration<double, std::micro>(loop_->stats().jitter.percentile(0.99)).count();
  figures.wall_s = r.wall_s;
  figures.mode = to_string(options_.mode);
  figures.corrections = supervisor_->corrections();
  if (const auto* teach = supervisor_->teach_in()) {
    TeachInOutcome o;
    o.done = teach->phase() == routines::TeachInPhase::done;
    o.result = teach->result();
    o.failure = std::string(teach->failure().view());
    o.restored = !teach->switched() || o.done;
    o.units_per_mm = teach_in_encoder_->units_per_mm();
    if (o.done) o.taught = teach_in_encoder_->taught(o.result.total_resolution);
    figures.teach_in = schema::TeachInFigures{o.done, o.result.total_resolution, o.restored};
    r.teach_in = std::move(o);
  }
  report_safety(r, figures);
  journal_.close(figures);
  r.faults = journal_.summary().faults();
  r.summary_text = journal_.summary().to_text();
  return r;
}

}  // namespace cellctl::runtime
