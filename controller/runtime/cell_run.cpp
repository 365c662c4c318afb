#include "runtime/cell_run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <nlohmann/json.hpp>

#include "loop/control_stages.hpp"
#include "loop/realtime_setup.hpp"

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

}  // namespace

CellRun::CellRun(const config::CellConfig& cell, const recipe::Recipe& recipe, RunOptions options)
    : cell_(cell),
      recipe_(recipe),
      program_(recipe::unroll(recipe)),
      options_(std::move(options)),
      clock_(options_.mode == RunMode::virtual_time ? static_cast<const link::Clock&>(virtual_clock_)
                                                    : static_cast<const link::Clock&>(real_clock_)),
      journal_(options_.journal_dir,
               options_.mode == RunMode::virtual_time ? journal::WhenFull::wait
                                                      : journal::WhenFull::drop_and_count,
               options_.record_header),
      monitor_(cell) {
  if (options_.mode == RunMode::virtual_time)
    waiter_ = std::make_unique<loop::VirtualWaiter>(virtual_clock_);
  else
    waiter_ = std::make_unique<loop::MonotonicWaiter>();
  if (!options_.faults.empty()) {
    if (options_.mode == RunMode::hardware)
      throw std::invalid_argument("faults are rehearsed on emulators only (--emulate or --virtual-time)");
    rehearsal_ = std::make_unique<FaultRehearsal>(options_.faults, cell);
  }
  try {
    links_ = std::make_unique<CellLinks>(cell, options_.mode, clock_, options_.trace,
                                         rehearsal_ ? rehearsal_->lines() : std::bitset<cell::kDevices>{});
    if (links_->any_emulated()) {
      if (!options_.emulators) options_.emulators = load_emulator_setup(cell);
      emulated_ = std::make_unique<EmulatedCell>(cell, *options_.emulators, links_->device());
    }
    devices_ = std::make_unique<CellDevices>(cell, links_->master());
  } catch (const std::exception& e) {
    // A port that did not open (or a device set-up refused): the record says why nothing ran.
    journal_.close({{"outcome", "not started"}, {"reason", e.what()}});
    throw;
  }
  supervisor_ = std::make_unique<supervisor::Supervisor>(
      cell, recipe, program_, journal_, cell.loop.period_ms / 1000.0, settings_for(cell, options_));
  loop_ = std::make_unique<loop::Loop>(clock_, *waiter_, period_of(cell), loop::kControlStages, &real_clock_);
  state_.axis_count = static_cast<std::uint8_t>(cell.axes.size());
}

CellRun::~CellRun() {
  emulators_stop_.store(true);
  if (emulator_thread_.joinable()) emulator_thread_.join();
}

void CellRun::run_emulator_thread() {
  // Emulated devices behind pseudo-terminals answer like hardware, on their own time.
  while (!emulators_stop_.load()) {
    const auto now = real_clock_.now();
    if (rehearsal_) rehearsal_->drive_emulators(now, *emulated_);
    emulated_->poll(now);
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

void CellRun::take_commands(double t, std::atomic<bool>& interrupt) {
  if (interrupt.exchange(false)) {
    interrupted_ = true;
    if (operator_stop_) emergency_stop_ = true;
    operator_stop_ = true;
  }
  if (terminate_ && terminate_->exchange(false)) {
    interrupted_ = true;
    request(supervisor::Command::stop);  // SIGTERM: a controlled stop, whatever stops.operator says
  }
  while (const auto text = operator_notes_.pop()) journal_.post(t, journal::Note{*text});
  const unsigned pending = requested_.exchange(0);
  // Strongest first, so that a stop typed right after a hold is never lost behind it.
  using supervisor::Command;
  for (const auto cmd :
       {Command::abort, Command::stop, Command::hold, Command::reset, Command::unhold, Command::start}) {
    if ((pending & bit(cmd)) == 0) continue;
    if (cmd == Command::reset) {
      // The devices are told to clear their own latched faults (the converter's CMD System Reset) and
      // the monitor judges its latches now: a converter fault is gone by the operator's next reset.
      supervisor_->reset_devices();
      judge_reset(t);
      continue;
    }
    if (!supervisor_->command(cmd, "operator", t)) journal_.post(t, journal::Note{supervisor_->refusal()});
  }
}

void CellRun::judge_reset(double t) {
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
    journal_.post(
        t, journal::Note{journal::Text::format("reset refused: the cause of {} is still present", still)});
    if (had_stop) operator_stop_ = true;
    return;
  }
  // Held by a category-2 stop, the run goes on: a reset clears the latches, unhold resumes. Only a
  // run that has ended goes back to Idle.
  if (!supervisor::is_final(supervisor_->state())) {
    journal_.post(
        t, journal::Note{journal::Text::format("faults reset in state {}", to_string(supervisor_->state()))});
    return;
  }
  if (!supervisor_->command(supervisor::Command::reset, "operator", t))
    journal_.post(t, journal::Note{supervisor_->refusal()});
}

void CellRun::report_devices(double t, RunResult& r) {
  // What the sessions know that the cell state could not carry (it holds no text): after the loop,
  // so composing it allocates nowhere near the cycle.
  const auto note = [&](std::string text) {
    journal_.post(t, journal::Note{journal::Text::format("{}", text)});
    r.device_notes.push_back(std::move(text));
  };
  static constexpr const char* kNames[cell::kDevices] = {"SCU", "spindle", "encoder"};
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    const auto* s = devices_->sessions()[d];
    if (s && s->lifecycle() == link::Lifecycle::fault)
      note(std::string(kNames[d]) + ": " + s->fault_reason());
  }
  if (auto* sp = devices_->spindle(); sp && sp->snapshot().start_refused)
    note("spindle: " + sp->snapshot().start_refused_reason);
  if (auto* enc = devices_->encoder(); enc && !enc->restart_reason().empty())
    note("encoder: DP start-up begun again: " + enc->restart_reason());
}

void CellRun::report_safety(RunResult& r, nlohmann::json& extra) const {
  r.safety = safe_stop_->verdicts();
  nlohmann::json devices = nlohmann::json::object();
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    if (!r.safety[d]) continue;
    devices[cell::to_string(static_cast<cell::Device>(d))] = {{"safe", to_string(r.safety[d]->safe)},
                                                               {"evidence", r.safety[d]->evidence}};
  }
  extra["devices"] = devices;
  if (!first_fault_ || supervisor_->state() == supervisor::State::complete) return;
  // A link that failed is named as the link (device, symptom, since when), whatever rule latched.
  const auto& f = *first_fault_;
  std::optional<cell::Device> lost;
  double since = 0.0;
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    const auto dev = static_cast<cell::Device>(d);
    const auto at = safe_stop_->lost_at_s(dev);
    if (at && *at <= f.t && (!lost || *at < since)) {
      lost = dev;
      since = *at;
    }
  }
  nlohmann::json ended{{"t", journal::round_ms(f.t)}, {"rule", monitor::to_string(f.rule)}};
  if (lost) {
    ended["kind"] = "link";
    ended["device"] = cell::to_string(*lost);
    ended["symptom"] = safe_stop_->lost_reason(*lost);
    ended["since_s"] = journal::round_ms(since);
    r.ended_by = fmt::format("{} link fault since {:.3f} s: {}", cell::to_string(*lost), since,
                             safe_stop_->lost_reason(*lost));
  } else {
    const bool by_operator = f.rule == monitor::Rule::operator_stop || f.rule == monitor::Rule::emergency_stop;
    ended["kind"] = by_operator ? "operator" : "monitor";
    ended["detail"] = std::string(f.detail.view());
    r.ended_by = fmt::format("{} at {:.3f} s: {}", monitor::to_string(f.rule), f.t, f.detail.view());
  }
  extra["ended_by"] = ended;
}

void CellRun::publish_status(double t) {
  StatusView v;
  v.t = t;
  v.state = supervisor_->state();
  v.steps = static_cast<std::uint32_t>(supervisor_->step_count());
  v.step = static_cast<std::uint32_t>(std::min(supervisor_->step_index() + 1, supervisor_->step_count()));
  if (const auto* ins = supervisor_->current()) v.label = ins->label;
  v.axes = state_.axis_count;
  for (std::size_t i = 0; i < state_.axis_count; ++i) {
    v.position_mm[i] = state_.axes[i].position_mm();
    v.position_known[i] = state_.axes[i].present;
  }
  v.spindle_hz = state_.spindle.actual_hz;
  v.spindle_set_hz = supervisor_->intents().spindle.run ? supervisor_->intents().spindle.frequency_hz : 0.0;
  for (std::size_t r = 0; r < monitor::kRuleCount; ++r) {
    if (!monitor_.latch(static_cast<monitor::Rule>(r)).active) continue;
    v.fault = true;
    v.first_fault = static_cast<monitor::Rule>(r);
    break;
  }
  board_.publish(v);
}

void CellRun::cycle(link::TimePoint now, std::atomic<bool>& interrupt) {
  const double t = link::to_seconds(now - start_);
  if (hook_) hook_(t, *this);
  if (rehearsal_) rehearsal_->post_journal(now, t, journal_);
  take_commands(t, interrupt);
  {  // the stages, timed back to back; the last ends with this block
    auto stages = loop_->stage_sequence();
    stages.begin(index(ControlStage::read_sessions));
    if (emulated_ && options_.mode == RunMode::virtual_time) {
      if (rehearsal_) rehearsal_->drive_emulators(now, *emulated_);
      emulated_->poll(now);
    }
    devices_->receive(now);

    stages.begin(index(ControlStage::state));
    devices_->read(now, state_);
    safe_stop_->observe(now);

    stages.begin(index(ControlStage::monitor));
    const auto fresh =
        monitor_.evaluate(state_, {.stop = operator_stop_, .emergency_stop = emergency_stop_}, t);
    for (std::size_t r = 0; r < monitor::kRuleCount; ++r) {
      if (!fresh.test(r)) continue;
      const auto rule = static_cast<monitor::Rule>(r);
      const auto& latch = monitor_.latch(rule);
      journal_.post(t, journal::Fault{monitor::to_string(rule), static_cast<std::uint8_t>(latch.category),
                                      latch.detail});
      if (!first_fault_ && !shutdown_since_) first_fault_.emplace(FirstFault{rule, t, latch.detail});
    }

    stages.begin(index(ControlStage::supervisor));
    supervisor_->step(state_, monitor_.demanded_stop(), t);
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
    if (shutdown_since_)
      safe_stop_->step(now);  // lost devices: port reopened, stop sent again until confirmed or bounded
    else
      devices_->apply(supervisor_->intents());
    devices_->transmit(now);  // what this cycle decided goes out in this cycle
  }
  if (shutdown_since_ && safe_stop_->done()) loop_stop_.store(true);
  publish_status(t);
}

RunResult CellRun::run(std::atomic<bool>& interrupt, std::atomic<bool>* terminate) {
  terminate_ = terminate;
  if (options_.mode != RunMode::virtual_time && cell_.loop.realtime) {
    const auto report = loop::apply_realtime(
        {.fifo_priority = cell_.loop.priority, .lock_memory = true, .cpu = cell_.loop.cpu});
    realtime_warnings_ = report.warnings();
  }
  const auto wall_start = std::chrono::steady_clock::now();
  start_ = clock_.now();
  links_->start_trace_clock(start_);
  if (rehearsal_) rehearsal_->start(start_, links_->fault_links());
  if (emulated_ && options_.mode != RunMode::virtual_time)
    emulator_thread_ = std::thread([this] { run_emulator_thread(); });

  safe_stop_ = std::make_unique<SafeStop>(cell_, *devices_, *links_,
                                          std::chrono::duration_cast<link::Duration>(
                                              std::chrono::duration<double>(options_.shutdown_timeout_s)),
                                          start_);
  devices_->activate(start_);
  (void)supervisor_->command(supervisor::Command::start, "cellctl run", 0.0);
  loop_->run([this, &interrupt](link::TimePoint now, std::uint64_t) { cycle(now, interrupt); }, loop_stop_);

  emulators_stop_.store(true);
  if (emulator_thread_.joinable()) emulator_thread_.join();

  RunResult r;
  if (rehearsal_) rehearsal_->post_run_end(link::to_seconds(clock_.now() - start_), journal_);
  report_devices(link::to_seconds(clock_.now() - start_), r);
  r.final_state = supervisor_->state();
  r.failure = std::string(supervisor_->failure().view());
  r.interrupted = interrupted_;
  r.duration_s = link::to_seconds(clock_.now() - start_);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  r.cycles = loop_->stats().cycles;
  r.loop_summary = loop_->summary();
  nlohmann::json extra;
  extra["cycles"] = r.cycles;
  extra["overrun_cycles"] = loop_->stats().overrun_cycles;
  extra["missed_deadlines"] = loop_->stats().missed_deadlines;
  extra["jitter_p99_us"] =
      std::chrono::duration<double, std::micro>(loop_->stats().jitter.percentile(0.99)).count();
  extra["wall_s"] = r.wall_s;
  extra["mode"] = to_string(options_.mode);
  extra["corrections"] = supervisor_->corrections();
  report_safety(r, extra);
  journal_.close(extra);
  r.faults = journal_.summary().faults();
  r.summary_text = journal_.summary().to_text();
  return r;
}

}  // namespace cellctl::runtime
