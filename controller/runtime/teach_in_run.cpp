#include "runtime/teach_in_run.hpp"

#include <fmt/format.h>

#include "loop/control_stages.hpp"

namespace cellctl::runtime {

TeachInRun::TeachInRun(const config::CellConfig& cell, const routines::TeachInRequest& request,
                       TeachInRunOptions options)
    : cell_(cell),
      options_(std::move(options)),
      clock_(run_clock(options_.mode, real_clock_, virtual_clock_)),
      journal_(options_.journal_dir, when_writer_full(options_.mode), options_.record_header),
      monitor_(cell) {
  try {
    if (!cell.encoder) throw std::invalid_argument("the cell has no encoder: section: nothing to teach");
    parts_ = open_cell_parts(cell, options_.mode, clock_, virtual_clock_, options_.trace, options_.faults,
                             options_.emulators);
    encoder_ = std::make_unique<TeachInEncoder>(*parts_.devices->encoder(), cell.encoder->session);
  } catch (const std::exception& e) {
    journal_.close({{"outcome", "not started"}, {"reason", e.what()}});
    throw;
  }
  routine_ = std::make_unique<routines::TeachIn>(cell, *encoder_, request, cell.loop.period_ms / 1000.0);
  loop_ = std::make_unique<loop::Loop>(clock_, *parts_.waiter, link::milliseconds(cell.loop.period_ms),
                                       loop::kControlStages, &real_clock_);
  state_.axis_count = static_cast<std::uint8_t>(cell.axes.size());
}

TeachInRun::~TeachInRun() {
  emulators_stop_.store(true);
  if (emulator_thread_.joinable()) emulator_thread_.join();
}

void TeachInRun::cycle(link::TimePoint now, std::atomic<bool>& interrupt,
                       const std::function<void(const TeachInProgress&)>& progress) {
  const double t = link::to_seconds(now - start_);
  if (hook_) hook_(t, *this);
  if (parts_.rehearsal) parts_.rehearsal->post_journal(now, t, journal_);
  if (interrupt.exchange(false) && !routine_->finished()) {
    interrupted_ = true;
    routine_->abort(t);
  }
  if (confirm_.exchange(false)) routine_->confirm();
  if (parts_.emulated && options_.mode == RunMode::virtual_time) {
    if (parts_.rehearsal) parts_.rehearsal->drive_emulators(now, *parts_.emulated);
    parts_.emulated->poll(now);
  }
  parts_.devices->receive(now);
  encoder_->step(now);
  parts_.devices->read(now, state_);
  routine_->adjust(state_);

  const auto fresh = monitor_.evaluate(state_, {}, t);
  std::string_view stop_reason;
  for (std::size_t r = 0; r < monitor::kRuleCount; ++r) {
    const auto rule = static_cast<monitor::Rule>(r);
    const auto& latch = monitor_.latch(rule);
    if (fresh.test(r))
      journal_.post(t, journal::Fault{monitor::to_string(rule), static_cast<std::uint8_t>(latch.category),
                                      latch.detail});
    if (latch.active && stop_reason.empty()) stop_reason = latch.detail.view();
  }
  routine_->step(state_, monitor_.demanded_stop(), stop_reason, t);
  monitor_.expect_spindle(false, 0.0);
  monitor_.expect_axes(routine_->intents());
  // Armed while the routine moves the axis; the encoder leaves data exchange on purpose in between.
  if (routine_->moving() && !monitor_.armed()) monitor_.arm();
  if (!routine_->moving() && monitor_.armed()) monitor_.disarm();

  if (routine_->phase() != last_phase_) {
    last_phase_ = routine_->phase();
    journal_.post(t, journal::Note{journal::Text::format("teach-in: {}", routines::to_string(last_phase_))});
    next_progress_t_ = t;
  }
  if (progress && t >= next_progress_t_) {
    next_progress_t_ = t + 0.5;
    TeachInProgress p;
    p.t = t;
    p.phase = routine_->phase();
    p.prompt = std::string(routine_->prompt().view());
    for (std::size_t i = 0; i < cell_.axes.size(); ++i)
      if (cell_.axes[i].encoder) {
        p.scu_mm = state_.axes[i].scu_mm;
        p.encoder_mm = state_.encoder.mm;
      }
    progress(p);
  }

  if (routine_->finished() && !shutdown_since_) {
    parts_.devices->deactivate(now);
    monitor_.disarm();
    shutdown_since_ = now;
  }
  if (!shutdown_since_) parts_.devices->apply(routine_->intents());
  parts_.devices->transmit(now);
  if (shutdown_since_ && (parts_.devices->all_inactive() ||
                          link::to_seconds(now - *shutdown_since_) > options_.shutdown_timeout_s))
    loop_stop_.store(true);
}

TeachInOutcome TeachInRun::run(std::atomic<bool>& interrupt,
                               const std::function<void(const TeachInProgress&)>& progress) {
  start_ = clock_.now();
  parts_.links->start_trace_clock(start_);
  if (parts_.rehearsal) parts_.rehearsal->start(start_, parts_.links->fault_links());
  if (parts_.emulated && options_.mode != RunMode::virtual_time)
    emulator_thread_ = std::thread(
        [this] { serve_emulators(emulators_stop_, real_clock_, parts_.rehearsal.get(), *parts_.emulated); });
  parts_.devices->activate(start_);
  loop_->run([&](link::TimePoint now, std::uint64_t) { cycle(now, interrupt, progress); }, loop_stop_);
  emulators_stop_.store(true);
  if (emulator_thread_.joinable()) emulator_thread_.join();

  TeachInOutcome o;
  const double t = link::to_seconds(clock_.now() - start_);
  if (parts_.rehearsal) parts_.rehearsal->post_run_end(t, journal_);
  o.done = routine_->phase() == routines::TeachInPhase::done;
  o.result = routine_->result();
  o.failure = std::string(routine_->failure().view());
  o.restored = !routine_->switched() || o.done;
  o.interrupted = interrupted_;
  o.units_per_mm = encoder_->units_per_mm();
  if (o.done) o.taught = encoder_->taught(o.result.total_resolution);
  static constexpr const char* kNames[cell::kDevices] = {"SCU", "spindle", "encoder"};
  for (std::size_t d = 0; d < cell::kDevices; ++d) {
    const auto* s = parts_.devices->sessions()[d];
    if (s && s->lifecycle() == link::Lifecycle::fault)
      o.device_notes.push_back(std::string(kNames[d]) + ": " + s->fault_reason());
  }
  nlohmann::json extra;
  extra["outcome"] = o.done ? "taught" : "failed";
  if (!o.done) extra["reason"] = o.failure;
  extra["total_resolution"] = o.result.total_resolution;
  extra["mode"] = to_string(options_.mode);
  journal_.close(extra);
  return o;
}

}  // namespace cellctl::runtime
