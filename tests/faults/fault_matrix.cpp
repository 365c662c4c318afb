#include "faults/fault_matrix.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>
#include <stdexcept>

#include "emulation/emulator_setup.hpp"
#include "recipe/recipe_loader.hpp"
#include "runtime/cell_run.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::faults {
namespace {

std::size_t index(cell::Device d) noexcept {
  return static_cast<std::size_t>(d);
}

double ms(link::Duration d) noexcept {
  return link::to_milliseconds(d);
}

bool is_line_fault(FaultClass f) noexcept {
  return f != FaultClass::error && f != FaultClass::delay_below;
}

// A run that has not ended this long after its start hangs: the harness stops it (Ctrl-C twice), and
// gives up on it altogether kGiveUpS later. The longest run of the matrix ends by itself in about 6 s.
constexpr double kHangS = 60.0;
constexpr double kGiveUpS = 30.0;

// The longest a device's reply may take and still count, on the shipped config: the SCU's and the
// converter's reply time-outs, the DP master's lost_slave_time for the encoder.
double link_limit_ms(cell::Device d, const config::CellConfig& cell) {
  switch (d) {
    case cell::Device::scu:
      return ms(cell.scu->session.reply_timeout);
    case cell::Device::spindle:
      return ms(cell.spindle->session.reply_timeout);
    case cell::Device::encoder:
      return ms(cell.encoder->session.bus.lost_slave_time);
  }
  return 0.0;
}

// Bound from the injection to the first monitor fault, per class and device, with its reasoning.
std::pair<double, std::string> detection_bound(const MatrixCase& c, const config::CellConfig& cell) {
  const double silence = cell.limits.link_silence_ms;
  const double lost = ms(cell.encoder->session.bus.lost_slave_time);
  const bool encoder = c.device == cell::Device::encoder;
  switch (c.fault) {
    case FaultClass::disconnect:
      // The port fails the next read or write: SCU and converter sessions fault at once. The DP master
      // sees a slave that stopped answering and loses it after lost_slave_time.
      if (encoder) return {lost + 50.0, fmt::format("lost_slave_time {:g} ms + 50 ms", lost)};
      return {5.0, "the next read or write fails (5 cycles)"};
    case FaultClass::silent:
    case FaultClass::corrupt:
    case FaultClass::delay_above:
      // No good reply gets through: silence counts from the last good reply, which came before the
      // injection. The encoder: under corruption a short telegram gets through now and then, so up to
      // two lost_slave_times.
      if (encoder) return {2 * lost + 50.0, fmt::format("2 × lost_slave_time {:g} ms + 50 ms", lost)};
      return {silence + 50.0, fmt::format("link_silence {:g} ms + 50 ms", silence)};
    case FaultClass::garbage:
      // Noise damages most telegrams, not all: the link goes silent once enough fail in a row.
      return {1000.0, "noise: 1 s"};
    case FaultClass::error:
      switch (c.device) {
        case cell::Device::scu: {
          const double keepalive = ms(cell.scu->session.keepalive_period);
          return {keepalive + 50.0, fmt::format("next RC status: keep-alive {:g} ms + 50 ms", keepalive)};
        }
        case cell::Device::spindle: {
          const double poll = ms(cell.spindle->session.status_poll);
          return {poll + 50.0, fmt::format("next statusout: poll {:g} ms + 50 ms", poll)};
        }
        case cell::Device::encoder:
          return {50.0, "the next exchange's diagnosis flag + the diagnosis: 50 ms"};
      }
      break;
    case FaultClass::delay_below:
      return {0.0, "no fault"};
  }
  return {0.0, "?"};
}

// Bound from the injection to the plant at rest: the stop's way to the device and the stopping itself.
std::pair<double, std::string> safe_bound(const MatrixCase& c, double detect_ms) {
  constexpr double kAxesStopMs = 500.0;     // 10 mm/s at 40 mm/s² stops in 0.25 s; a fast stop sooner
  constexpr double kScuWatchdogMs = 500.0;  // RO Safety_ID 0: no RC for 0.5 s stops all motion
  constexpr double kRunDownMs = 1250.0;     // 400 Hz at 400 Hz/s: 1 s, + 250 ms
  const bool line_down = is_line_fault(c.fault);
  switch (c.activity) {
    case Activity::idle:
      return {detect_ms, "at rest already"};
    case Activity::moving:
      if (line_down && c.device == cell::Device::scu)
        return {std::max(kScuWatchdogMs, detect_ms) + kAxesStopMs,
                "the SCU's watchdog 500 ms (no RC through) + stopping 500 ms"};
      return {detect_ms + kAxesStopMs, "detected + stopping 500 ms"};
    case Activity::spindle_on:
      if (line_down && c.device == cell::Device::spindle)
        return {kLastingS * 1000.0 + kRunDownMs,
                "the stop gets through when the line is back (2 s) + run-down 1.25 s"};
      return {detect_ms + kRunDownMs, "detected + run-down 1.25 s"};
  }
  return {0.0, "?"};
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return s;
}

// What the journal says of the run: injection time, first fault, the summary and its devices.
void read_outcome(const std::filesystem::path& file, Outcome& o) {
  const auto lines = read_journal(file);
  std::optional<double> injected;
  for (const auto& j : lines) {
    const auto event = j.value("event", "");
    if (event == "fault_injected" && !injected) injected = j["t"].get<double>();
    if (event == "fault" && injected && !o.detected_ms) {
      o.detected_ms = (j["t"].get<double>() - *injected) * 1000.0;
      o.first_rule = j.value("rule", "");
      o.first_fault = o.first_rule + ": " + j.value("detail", "");
    }
  }
  o.summary = summary_of(lines);
  if (o.summary.is_null()) return;
  o.outcome = o.summary.value("outcome", "");
  o.devices = device_safety(o.summary);
}

}  // namespace

std::string_view to_string(FaultClass c) noexcept {
  constexpr std::string_view names[] = {"silent",      "disconnect",  "corrupt", "garbage",
                                        "delay_below", "delay_above", "error"};
  return names[static_cast<std::size_t>(c)];
}

std::string_view to_string(Activity a) noexcept {
  constexpr std::string_view names[] = {"idle", "moving", "spindle_on"};
  return names[static_cast<std::size_t>(a)];
}

std::vector<MatrixCase> all_cases() {
  std::vector<MatrixCase> out;
  for (const auto d : kDevices)
    for (const auto f : kFaultClasses)
      for (const auto a : kActivities) out.push_back({d, f, a});
  const auto cell = matrix_cell();
  for (const auto d : kDevices)
    for (const double delay : kServiceDelaysMs)
      if (delay < link_limit_ms(d, cell))
        out.push_back({d, FaultClass::delay_below, Activity::moving, delay});
  return out;
}

std::string name_of(const MatrixCase& c) {
  const auto fault = c.delay_ms > 0.0 ? fmt::format("{}={:g}", to_string(c.fault), c.delay_ms)
                                      : std::string(to_string(c.fault));
  return fmt::format("{}/{}/{}", cell::to_string(c.device), fault, to_string(c.activity));
}

double delay_ms(const MatrixCase& c, const config::CellConfig& cell) {
  if (c.delay_ms > 0.0) return c.delay_ms;
  const double limit = link_limit_ms(c.device, cell);
  if (c.fault == FaultClass::delay_below) return limit / 2.0;
  return limit + cell.limits.link_silence_ms;
}

std::string fault_spec_text(const MatrixCase& c, const config::CellConfig& cell) {
  std::string kind;
  switch (c.fault) {
    case FaultClass::delay_below:
    case FaultClass::delay_above:
      kind = fmt::format("delay={:g}", delay_ms(c, cell));
      break;
    default:
      kind = std::string(to_string(c.fault));
  }
  return fmt::format("{}:{}@{:g}+{:g}", cell::to_string(c.device), kind, kInjectAtS, kLastingS);
}

Expectation expectation(const MatrixCase& c, const config::CellConfig& cell) {
  Expectation e;
  e.safe = {Safe::observed, Safe::observed, Safe::observed};
  if (c.fault == FaultClass::delay_below) {
    // Late replies within the device's time-out: nothing faults, the recipe completes.
    e.fault_detected = false;
    e.exit_status = 0;
    e.safe_ms = 0.0;
    e.why = fmt::format("{:g} ms: half the device's reply limit", delay_ms(c, cell));
    return e;
  }
  const auto [detect, detect_why] = detection_bound(c, cell);
  const auto [safe, safe_why] = safe_bound(c, detect);
  e.detect_ms = detect;
  e.safe_ms = safe;
  e.detect_why = detect_why;
  e.why = detect_why + "; " + safe_why;
  e.may_ride_through = c.fault == FaultClass::garbage;
  if (c.fault == FaultClass::error) {
    switch (c.device) {
      case cell::Device::scu:
        e.first_rules = {"scu_error"};
        break;
      case cell::Device::spindle:
        e.first_rules = {"spindle_fault", "spindle_temperature"};
        break;
      case cell::Device::encoder:
        e.first_rules = {"encoder_alarm", "encoder_diagnosis", "encoder_not_ready"};
        break;
    }
    return e;  // the device's link is fine: it confirms its stop
  }
  // A line fault is named as the link that failed, never as a disagreement of measurements.
  e.first_rules = c.device == cell::Device::encoder
                      ? std::vector<std::string>{"encoder_not_ready", "link_silent"}
                      : std::vector<std::string>{"link_silent"};
  // The SCU cannot confirm its stop while its line is down: bounded by its communication time-out
  // (0.5 s) + the actuators' stopping time. A port that is gone stays gone past that bound; over a
  // line that only loses or damages telegrams cellctl's requests may still reach the SCU, so it keeps
  // trying, and the stop may be confirmed once the line is back or a reply gets through the noise:
  // observed is as good. The converter's line is back after 2 s, well within the time cellctl keeps
  // sending the stop: observed. The encoder stops nothing; with its link lost it cannot watch the
  // axes to the end: bounded.
  if (c.device != cell::Device::spindle) e.safe[index(c.device)] = Safe::bounded;
  e.or_observed[index(cell::Device::scu)] =
      c.device == cell::Device::scu && c.fault != FaultClass::disconnect;
  return e;
}

config::CellConfig matrix_cell() {
  return config::load_cell_config(std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
}

std::filesystem::path recipe_of(Activity a) {
  return std::filesystem::path(CELLCTL_SOURCE_DIR) / "tests/faults/recipes" /
         (std::string(to_string(a)) + ".yaml");
}

Outcome run_case(const MatrixCase& c, const config::CellConfig& cell, const std::filesystem::path& work_dir,
                 bool keep) {
  Outcome o;
  std::string dir_name = name_of(c);
  std::replace(dir_name.begin(), dir_name.end(), '/', '-');
  const auto dir = work_dir / dir_name;
  std::filesystem::remove_all(dir);
  try {
    const auto recipe = recipe::load_recipe(recipe_of(c.activity), cell);
    auto parsed = runtime::parse_fault_spec(fault_spec_text(c, cell));
    if (const auto* bad = std::get_if<runtime::FaultSpecError>(&parsed))
      throw std::invalid_argument(fault_spec_text(c, cell) + ": " + bad->reason);
    runtime::RunOptions options;
    options.mode = runtime::RunMode::virtual_time;
    options.journal_dir = dir / "journal";
    options.faults = {std::get<runtime::FaultSpec>(parsed)};
    options.emulators = emulation::load_emulator_setup(cell);
    if (options.emulators->encoder) options.emulators->encoder->state_file = dir / "encoder.eeprom";
    runtime::CellRun run(cell, recipe, std::move(options));

    std::atomic<bool> interrupt{false};
    std::optional<double> moving_last;  // the last cycle the plant was not at rest
    run.on_cycle([&](double t, runtime::CellRun& r) {
      if (spindle_turning(*r.emulators()) || axes_moving(*r.emulators())) moving_last = t;
      if (t > kHangS && o.ended_by_itself) {
        o.ended_by_itself = false;
        interrupt.store(true);
      }
      if (!o.ended_by_itself && t > kHangS + 1.0) interrupt.store(true);  // the second: an emergency stop
      if (t > kHangS + kGiveUpS) throw std::runtime_error("the run did not end even when stopped");
    });
    const auto result = run.run(interrupt);
    o.final_state = result.final_state;
    o.ended_ms = (result.duration_s - kInjectAtS) * 1000.0;
    const bool at_rest = !spindle_turning(*run.emulators()) && !axes_moving(*run.emulators());
    if (at_rest) o.safe_ms = std::max(0.0, (moving_last.value_or(0.0) - kInjectAtS) * 1000.0);
  } catch (const std::exception& e) {
    o.setup_error = e.what();
  }
  read_outcome(dir / "journal" / "journal.jsonl", o);
  if (!keep) std::filesystem::remove_all(dir);
  return o;
}

std::optional<int> cellctl_exit_status(const MatrixCase& c, const config::CellConfig& cell,
                                       const std::filesystem::path& cellctl,
                                       const std::filesystem::path& work_dir) {
  std::string dir_name = name_of(c);
  std::replace(dir_name.begin(), dir_name.end(), '/', '-');
  const auto dir = work_dir / (dir_name + "-cellctl");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // The shipped config with the encoder's EEPROM file in this directory, so no other run shares it.
  std::ifstream in(std::filesystem::path(CELLCTL_SOURCE_DIR) / "config/cell.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string eeprom = "state_file: /tmp/cellctl-encoder.eeprom";
  const auto at = text.find(eeprom);
  if (at == std::string::npos) return std::nullopt;
  text.replace(at, eeprom.size(), "state_file: " + (dir / "encoder.eeprom").string());
  std::ofstream(dir / "cell.yaml") << text;

  const std::vector<std::string> args = {cellctl.string(),
                                         "run",
                                         recipe_of(c.activity).string(),
                                         "--virtual-time",
                                         "-c",
                                         (dir / "cell.yaml").string(),
                                         "--journal",
                                         (dir / "journal").string(),
                                         "--fault",
                                         fault_spec_text(c, cell)};
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  const auto out = (dir / "output.txt").string();
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return std::nullopt;
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return std::nullopt;
  std::filesystem::remove_all(dir);
  return WEXITSTATUS(status);
}

std::vector<std::string> verdict(const MatrixCase& c, const Expectation& expected, const Outcome& o) {
  std::vector<std::string> out;
  Expectation e = expected;
  if (e.may_ride_through && !o.detected_ms) {
    e.fault_detected = false;
    e.safe = {Safe::observed, Safe::observed, Safe::observed};
    e.exit_status = 0;
  }
  const auto fail = [&](std::string s) { out.push_back(std::move(s)); };
  const std::string device(cell::to_string(c.device));
  if (!o.setup_error.empty()) fail("the run failed: " + o.setup_error);
  if (!o.ended_by_itself) fail(fmt::format("hangs: not ended {:g} s after the start", kHangS));
  if (o.summary.is_null()) {
    fail("the journal was not closed with a summary");
    return out;
  }
  const auto faults = o.summary.value("faults", nlohmann::json::array());
  const auto names = [&](const std::string& text) {
    return std::any_of(faults.begin(), faults.end(), [&](const nlohmann::json& f) {
      return f.is_string() && f.get<std::string>().find(text) != std::string::npos;
    });
  };
  if (!names("injected: ")) fail("the summary does not name the injected fault");

  if (e.fault_detected) {
    if (!o.detected_ms) {
      fail("no fault detected");
    } else {
      if (*o.detected_ms > e.detect_ms)
        fail(fmt::format("detected after {:.0f} ms > {:.0f} ms", *o.detected_ms, e.detect_ms));
      if (!e.first_rules.empty() &&
          std::find(e.first_rules.begin(), e.first_rules.end(), o.first_rule) == e.first_rules.end())
        fail("first fault is " + o.first_fault + ", not the " + device + "'s link or own fault");
      if (lower(o.first_fault).find(device) == std::string::npos)
        fail("first fault does not name the " + device + ": " + o.first_fault);
      if (!names(o.first_rule)) fail("the summary does not name the fault " + o.first_rule);
    }
    if (o.final_state == supervisor::State::complete) fail("the recipe completed despite the fault");
  } else {
    if (o.detected_ms) fail("a delay below the limit caused a fault: " + o.first_fault);
    if (o.final_state != supervisor::State::complete)
      fail(fmt::format("the recipe did not complete ({})", supervisor::to_string(o.final_state)));
  }
  if (!o.safe_ms)
    fail("the plant is not at rest when the run ends");
  else if (e.fault_detected && *o.safe_ms > e.safe_ms)
    fail(fmt::format("plant at rest after {:.0f} ms > {:.0f} ms", *o.safe_ms, e.safe_ms));

  if (!o.devices.present) {
    fail("the summary has no devices object");
  } else {
    for (const auto d : kDevices) {
      const auto i = index(d);
      if (!o.devices.safe[i])
        fail(fmt::format("devices.{}.safe missing or not observed|bounded|unknown", cell::to_string(d)));
      else if (*o.devices.safe[i] != e.safe[i] && !(e.or_observed[i] && *o.devices.safe[i] == Safe::observed))
        fail(fmt::format("{} safe {} (expected {}{}): {}", cell::to_string(d), to_string(*o.devices.safe[i]),
                         to_string(e.safe[i]), e.or_observed[i] ? " or observed" : "",
                         o.devices.evidence[i]));
    }
  }
  if (o.exit_status && *o.exit_status != e.exit_status)
    fail(fmt::format("exit status {} (expected {})", *o.exit_status, e.exit_status));
  return out;
}

}  // namespace cellctl::faults
