// The whole cell's control cycle — sessions, emulators, monitor, supervisor, journal posting — on
// the shipped cell config and demo recipe. Ratios against the same run's reference:
//
//   BM_CellVirtualTime    virtual duration of the run / wall time it took (goal >= 1000), and heap
//                         allocations on the loop's thread per cycle while the supervisor is in
//                         Execute, i.e. after start-up (goal 0). Repeated; min and median reported.
//                         Stage compute / period too, where the loop times stages on the monotonic
//                         clock ("read sessions" then includes stepping the emulators).
//   BM_CellFaultReaction  a cause injected 15 s into Execute (a device falls silent, reports a fault,
//                         drops replies): allocations on the loop's thread from the injection until
//                         the run is Stopped/Aborted (goal 0: the fault paths are in the cycle too).
//   BM_CellRealTime       the cycle on the monotonic clock, emulators behind pseudo-terminals on
//                         their own thread as in `cellctl run --emulate`: compute time of each stage
//                         (mean and p99) / the loop period.
//
//   cell_bench [--repetitions=3] [--realtime_s=3] [--fifo] [--cell=config/cell.yaml]
//              [--recipe=recipes/demo.yaml]
//
// --realtime_s=0 skips the real-time run; a recipe longer than that is stopped (operator stop) then.
// --fifo keeps the config's SCHED_FIFO + mlockall request (off by default: a shared machine).
//
// Finding an allocation in the cycle: the loop runs on the main thread and cellbench_in_window is
// 1 while a count is taken, so with a gdb command file holding
//   set pagination off
//   break operator new(unsigned long) if cellbench_in_window && $_thread == 1
//   commands 1
//   bt 12
//   cont
//   end
//   run
// `gdb -batch -x that-file --args cell_bench --repetitions=1 --realtime_s=0` prints each one's stack.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config/cell_config.hpp"
#include "journal/event_listener.hpp"
#include "plant_link/plant_link.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/cell_run.hpp"
#include "support/allocation_counter.hpp"
#include "support/execute_window.hpp"
#include "web/operator_page.hpp"

// Read by a debugger's breakpoint condition (see above); a C name so that it is easy to spell.
extern "C" {
volatile int cellbench_in_window = 0;
}

namespace {

using namespace cellctl;

struct Options {
  int repetitions = 3;
  double realtime_s = 3.0;
  bool fifo = false;
  std::filesystem::path cell = std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml";
  std::filesystem::path recipe = std::filesystem::path(CELLCTL_SOURCE_DIR) / "recipes/demo.yaml";
};

Options g_options;

// Takes the options Google Benchmark did not consume; unknown ones are an error.
bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&](std::string_view key) -> const char* {
      return a.substr(0, key.size()) == key ? argv[i] + key.size() : nullptr;
    };
    if (const char* r = value("--repetitions=")) {
      o.repetitions = std::atoi(r);
    } else if (const char* s = value("--realtime_s=")) {
      o.realtime_s = std::atof(s);
    } else if (const char* c = value("--cell=")) {
      o.cell = c;
    } else if (const char* p = value("--recipe=")) {
      o.recipe = p;
    } else if (a == "--fifo") {
      o.fifo = true;
    } else {
      std::fprintf(stderr, "cell_bench: unknown option %s\n", argv[i]);
      return false;
    }
  }
  return o.repetitions > 0 && o.realtime_s >= 0.0;
}

// A fresh directory per run for the journal and the encoder's EEPROM file, removed afterwards.
class ScratchDir {
 public:
  explicit ScratchDir(std::string_view tag)
      : path_(std::filesystem::temp_directory_path() /
              (std::string("cellctl-bench-") + std::string(tag) + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

struct Setup {
  config::CellConfig cell;
  emulation::EmulatorSetup emulators;
  recipe::Recipe recipe;
};

Setup load(const ScratchDir& dir) {
  Setup s;
  s.cell = config::load_cell_config(g_options.cell);
  s.emulators = emulation::load_emulator_setup(s.cell);
  if (s.emulators.encoder) s.emulators.encoder->state_file = dir.path() / "encoder.eeprom";
  s.cell.loop.realtime = g_options.fifo && s.cell.loop.realtime;
  s.recipe = recipe::load_recipe(g_options.recipe, s.cell);
  return s;
}

// The Execute window's allocation count (support/execute_window.hpp), with the debugger's flag.
struct ExecuteWindow : testing::ExecuteWindow {
  ExecuteWindow() { in_window = &cellbench_in_window; }
};

double per(double x, double y) {
  return y > 0.0 ? x / y : 0.0;
}

// The causes a fault run injects, by benchmark argument.
struct Cause {
  const char* name;
  void (*inject)(runtime::EmulatedCell&);
};
constexpr Cause kCauses[] = {
    {"spindle silent", [](runtime::EmulatedCell& e) { e.spindle()->set_silent(true); }},
    {"spindle fault 51", [](runtime::EmulatedCell& e) { e.spindle()->inject_fault(51); }},
    {"scu replies dropped", [](runtime::EmulatedCell& e) { e.scu()->drop_next_replies(1 << 20); }},
    {"scu actuator fault", [](runtime::EmulatedCell& e) { e.scu()->inject_actuator_fault(1); }},
    {"encoder silent", [](runtime::EmulatedCell& e) { e.encoder()->set_silent(true); }},
};
constexpr double kInjectAfterExecute_s = 15.0;  // the spindle is up and the axes are moving by then

// Heap allocations of the loop's thread from the cycle a cause is injected to the cycle the run is
// final (Stopped/Aborted): the whole fault reaction — sessions faulting, monitor latching, journal
// posting, the supervisor stopping — which the invariant wants allocation-free as well.
struct FaultWindow {
  std::optional<double> execute_t;
  std::optional<double> injected_t;
  std::optional<double> final_t;
  std::uint64_t cycles = 0;
  std::size_t at_inject = 0;
  std::size_t allocations = 0;

  void on_cycle(double t, runtime::CellRun& r, const Cause& cause) {
    const supervisor::State s = r.supervisor().state();
    if (!execute_t && s == supervisor::State::execute) execute_t = t;
    if (execute_t && !injected_t && t >= *execute_t + kInjectAfterExecute_s) {
      injected_t = t;
      at_inject = testing::thread_allocation_count();
      cellbench_in_window = 1;
      cause.inject(*r.emulators());
    }
    if (injected_t && !final_t) {
      if (supervisor::is_final(s)) {
        final_t = t;
        allocations = testing::thread_allocation_count() - at_inject;
        cellbench_in_window = 0;
      } else {
        ++cycles;
      }
    }
  }
};

void BM_CellFaultReaction(benchmark::State& state) {
  const Cause& cause = kCauses[static_cast<std::size_t>(state.range(0))];
  state.SetLabel(cause.name);
  const ScratchDir dir("fault");
  Setup setup = load(dir);
  runtime::RunOptions o;
  o.emulators = setup.emulators;
  o.mode = runtime::RunMode::virtual_time;
  o.journal_dir = dir.path() / "journal";
  runtime::RunResult result;
  FaultWindow window;
  for (auto _ : state) {
    runtime::CellRun run(setup.cell, setup.recipe, o);
    run.on_cycle([&](double t, runtime::CellRun& r) { window.on_cycle(t, r, cause); });
    std::atomic<bool> interrupt{false};
    result = run.run(interrupt);
  }
  cellbench_in_window = 0;
  if (!window.final_t) {
    state.SkipWithError("the run did not end Stopped or Aborted after the cause");
    return;
  }
  state.counters["allocs_reaction"] = static_cast<double>(window.allocations);
  state.counters["allocs_per_cycle"] =
      per(static_cast<double>(window.allocations), static_cast<double>(window.cycles));
  state.counters["reaction_cycles"] = static_cast<double>(window.cycles);
  std::printf("%s: %s after %.3f s, %zu allocations in %llu cycles; %s\n", cause.name,
              std::string(to_string(result.final_state)).c_str(), *window.final_t - *window.injected_t,
              window.allocations, static_cast<unsigned long long>(window.cycles),
              result.faults.empty() ? "no fault latched" : result.faults.front().c_str());
}

// One "stage <name> mean M us, p50 A us, p99 B us, p99.9 C us, max D us" line of Loop::summary().
struct StageLine {
  std::string name;
  double mean_us = 0.0;
  double p99_us = 0.0;
  double max_us = 0.0;
};

// CellRun hands out the loop's statistics as Loop::summary() text only, so the stage lines are read
// back from it; a line that does not parse fails the benchmark rather than report a zero.
bool parse_stages(const std::string& summary, std::vector<StageLine>& out) {
  constexpr std::string_view kPrefix = "stage ";
  constexpr std::size_t kNameWidth = 16;  // "{:<16}" in Loop::summary()
  std::size_t pos = 0;
  while (pos < summary.size()) {
    const std::size_t end = std::min(summary.find('\n', pos), summary.size());
    const std::string line = summary.substr(pos, end - pos);
    pos = end + 1;
    if (line.rfind(kPrefix, 0) != 0) continue;
    StageLine s;
    s.name = line.substr(kPrefix.size(), kNameWidth);
    s.name.erase(s.name.find_last_not_of(' ') + 1);
    double p50 = 0.0;
    double p999 = 0.0;
    const std::string rest = line.substr(std::min(line.size(), kPrefix.size() + kNameWidth));
    if (std::sscanf(rest.c_str(), " mean %lf us, p50 %lf us, p99 %lf us, p99.9 %lf us, max %lf us",
                    &s.mean_us, &p50, &s.p99_us, &p999, &s.max_us) != 5)
      return false;
    for (char& c : s.name)
      if (c == ' ') c = '_';
    out.push_back(std::move(s));
  }
  return !out.empty();
}

// Each stage's mean and p99 compute time / the loop period as counters; false when the summary has
// no stage lines.
bool add_stage_counters(benchmark::State& state, const std::string& summary, double period_us) {
  std::vector<StageLine> stages;
  if (!parse_stages(summary, stages)) return false;
  double mean_total = 0.0;
  for (const auto& s : stages) {
    state.counters[s.name + "_mean_per_period"] = s.mean_us / period_us;
    state.counters[s.name + "_p99_per_period"] = s.p99_us / period_us;
    mean_total += s.mean_us;
  }
  state.counters["compute_mean_per_period"] = mean_total / period_us;
  return true;
}

// range(0) == 1: the same run with the plant link (MQTT, to a loopback port where no broker listens:
// it keeps reconnecting and counts its drops, the worst case for it) and the web operator page on,
// both fed from the journal's thread: the loop's allocations per cycle and its stage times must not
// change.
void BM_CellVirtualTime(benchmark::State& state) {
  const bool plant_on = state.range(0) == 1;
  const ScratchDir dir(plant_on ? "virtual-plant" : "virtual");
  Setup setup = load(dir);
  runtime::RunOptions o;
  o.emulators = setup.emulators;
  o.mode = runtime::RunMode::virtual_time;
  o.journal_dir = dir.path() / "journal";
  runtime::RunResult result;
  ExecuteWindow window;
  double end_to_end_s = 0.0;
  for (auto _ : state) {
    const auto begin = std::chrono::steady_clock::now();
    runtime::CellRun run(setup.cell, setup.recipe, o);
    run.on_cycle([&window](double, runtime::CellRun& r) { window.on_cycle(r.supervisor().state()); });
    std::unique_ptr<plant_link::PlantLink> link;
    std::unique_ptr<web::OperatorPage> page;
    std::unique_ptr<journal::EventListeners> listeners;             // both, on the journal's thread
    command::Arbiter arbiter(std::chrono::milliseconds(2000), {});  // as `cellctl run` has it
    arbiter.attach(run.port());
    (void)arbiter.start({{}, std::chrono::steady_clock::now(), {}}, [] {
      return command::Taken{command::Taken::How::done, "started"};
    });
    if (plant_on) {
      const auto access = plant_link::fixed_run(arbiter, run.status(), "virtual-time");
      plant_link::LinkConfig lc;
      lc.cell = setup.cell.name;
      lc.client_id = "cell-bench";
      lc.port = 1;  // nothing listens there
      link = std::make_unique<plant_link::PlantLink>(lc, setup.cell, access);
      web::PageOptions po;
      po.port = 0;
      po.token = "bench-token-of-sixteen-bytes-or-more";
      page = std::make_unique<web::OperatorPage>(po, setup.cell, access);
      listeners = std::make_unique<journal::EventListeners>(
          std::initializer_list<journal::EventListener*>{&link->events(), &page->events()});
      run.listen(listeners.get());
    }
    std::atomic<bool> interrupt{false};
    result = run.run(interrupt);
    run.listen(nullptr);
    end_to_end_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  }
  cellbench_in_window = 0;
  if (result.final_state != supervisor::State::complete || !window.closed) {
    state.SkipWithError(("the recipe did not complete: " + result.failure).c_str());
    return;
  }
  // The loop's wall time (RunResult), and the whole run with set-up and the journal's close.
  state.counters["speedup"] = per(result.duration_s, result.wall_s);
  state.counters["speedup_end_to_end"] = per(result.duration_s, end_to_end_s);
  state.counters["virtual_s"] = result.duration_s;
  state.counters["cycles"] = static_cast<double>(result.cycles);
  state.counters["execute_cycles"] = static_cast<double>(window.cycles);
  state.counters["allocs_execute"] = static_cast<double>(window.allocations());
  state.counters["allocs_per_cycle"] =
      per(static_cast<double>(window.allocations()), static_cast<double>(window.cycles));
  state.counters["allocs_start_up"] = static_cast<double>(window.start_up());
  state.counters["allocs_after_execute"] = static_cast<double>(window.after());
  // Stage timers read the real clock here too; "read sessions" includes stepping the emulators.
  if (!add_stage_counters(state, result.loop_summary, setup.cell.loop.period_ms * 1000.0)) {
    state.SkipWithError("no stage lines in the loop summary");
    return;
  }
  std::printf(
      "virtual %.2f s in %.3f s wall (loop), %.3f s end to end; %zu allocations in %llu Execute cycles "
      "(until %s)\n",
      result.duration_s, result.wall_s, end_to_end_s, window.allocations(),
      static_cast<unsigned long long>(window.cycles), std::string(to_string(window.ended_in)).c_str());
}

void BM_CellRealTime(benchmark::State& state) {
  const ScratchDir dir("realtime");
  Setup setup = load(dir);
  runtime::RunOptions o;
  o.emulators = setup.emulators;
  o.mode = runtime::RunMode::emulated;
  o.journal_dir = dir.path() / "journal";
  runtime::RunResult result;
  ExecuteWindow window;
  for (auto _ : state) {
    runtime::CellRun run(setup.cell, setup.recipe, o);
    bool stop_sent = false;
    run.on_cycle([&](double t, runtime::CellRun& r) {
      window.on_cycle(r.supervisor().state());
      if (!stop_sent && t >= g_options.realtime_s) {
        r.request(supervisor::Command::stop);
        stop_sent = true;
      }
    });
    std::atomic<bool> interrupt{false};
    result = run.run(interrupt);
    for (const auto& w : run.realtime_warnings()) std::printf("warning: %s\n", w.c_str());
  }
  cellbench_in_window = 0;
  if (!add_stage_counters(state, result.loop_summary, setup.cell.loop.period_ms * 1000.0)) {
    state.SkipWithError("no stage lines in the loop summary");
    return;
  }
  state.counters["cycles"] = static_cast<double>(result.cycles);
  state.counters["execute_cycles"] = static_cast<double>(window.cycles);
  state.counters["allocs_per_cycle"] =
      per(static_cast<double>(window.allocations()), static_cast<double>(window.cycles));
  std::printf("%s", result.loop_summary.c_str());
  std::printf("ended %s after %.2f s; %zu allocations in %llu Execute cycles\n",
              std::string(to_string(result.final_state)).c_str(), result.duration_s, window.allocations(),
              static_cast<unsigned long long>(window.cycles));
}

// A zero count means something only if the counter sees an allocation on this thread.
bool counter_sees_this_thread() {
  const std::size_t before = testing::thread_allocation_count();
  std::string probe(64, 'x');
  benchmark::DoNotOptimize(probe.data());
  return testing::thread_allocation_count() > before;
}

double minimum(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::min_element(v.begin(), v.end());
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (!parse(argc, argv, g_options)) return 2;
  if (!counter_sees_this_thread()) {
    std::fprintf(stderr, "cell_bench: the allocation counter is not linked in\n");
    return 1;
  }
  benchmark::RegisterBenchmark("BM_CellVirtualTime", BM_CellVirtualTime)
      ->Arg(0)
      ->Arg(1)
      ->Iterations(1)
      ->Repetitions(g_options.repetitions)
      ->ComputeStatistics("min", minimum)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_CellFaultReaction", BM_CellFaultReaction)
      ->DenseRange(0, static_cast<int>(std::size(kCauses)) - 1)
      ->Iterations(1)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond);
  if (g_options.realtime_s > 0.0)
    benchmark::RegisterBenchmark("BM_CellRealTime", BM_CellRealTime)
        ->Iterations(1)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
