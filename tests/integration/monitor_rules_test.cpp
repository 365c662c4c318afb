// Every safety-monitor rule, caused on purpose in a whole run in virtual time (emulators, SimLinks,
// sessions, monitor, supervisor, journal): the cell stops in the rule's configured category within a
// stated bound from the injection, the plant ends at rest and the journal names the cause.
//
// The shipped cell's categories: faults 1 (→ Stopped), links 0 (→ Aborted), operator stop 2 (→ Held);
// the emergency stop is always 0. The bounds follow from the shipped config: spindle status polled
// every 20 ms, SCU RC every 100 ms, encoder data exchange every 1 ms and its slave lost after 100 ms,
// link silence 300 ms. Reaching rest takes the ramps: axes 10 mm/s at 40 mm/s² (0.25 s), the spindle
// 400 Hz at 400 Hz/s (1 s).

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>

#include "encoder/diagnosis.hpp"
#include "fault_run.hpp"

namespace cellctl::testing {
namespace {

// The encoder's cyclic data at 19200 baud 8E1: a data exchange (13-byte request, 15-byte reply) takes
// about 17 ms on the line, so a change reaches the master within two exchanges.
constexpr double kEncoderDataMs = 40.0;
// A new diagnosis: DH in an exchange, then Slave_Diag (request and a 30-byte reply), then the next
// exchange.
constexpr double kEncoderDiagnosisMs = 100.0;
// The SCU's position and error word come with the RC reply, every 100 ms (keepalive), plus its
// reply time.
constexpr double kScuReplyMs = 130.0;
// The disagreement rule compares the encoder with the SCU's position of the last RC reply, allowing
// for the travel since the RC went out (the reading's age counts its round trip, about 12 ms at
// 38400 Bd): a disagreement growing at 0.5 mm/s is caught with the next reply or the one after, once it
// has also outgrown that round trip's travel at the traverse's 10 mm/s (0.12 mm: 240 ms more).
constexpr double kDisagreementMs = 2 * kScuReplyMs + 240.0;
// The spindle's statusout is polled every 20 ms; the values (frequency) every 250 ms.
constexpr double kSpindleStatusMs = 45.0;
constexpr double kSpindleValuesMs = 280.0;

// From the moment a category-1 stop is demanded to Stopped: the spindle's 1 s run-down dominates.
constexpr double kControlledStopS = 1.5;

class MonitorRule : public FaultRun {
 protected:
  void SetUp() override {
    FaultRun::SetUp();
    load_recipe_text(kTraverseRecipe);
  }

  // A category-1 ending: the fault latched within `bound_ms` of the cause, the supervisor went
  // Stopping at once, Stopped within kControlledStopS, the plant at rest, the journal says so.
  void expect_controlled_stop(const runtime::RunResult& r, const std::string& rule, double bound_ms) {
    report(rule, bound_ms);
    ASSERT_TRUE(timeline_.cause_t) << "the cause was never injected";
    const auto f = fault(rule);
    ASSERT_FALSE(f.is_null()) << "no fault event for " << rule << "\n" << r.summary_text;
    EXPECT_EQ(f["category"], 1);
    EXPECT_GE(reaction_ms(rule), 0.0);
    EXPECT_LE(reaction_ms(rule), bound_ms);
    const double fault_t = f["t"].get<double>();
    EXPECT_NEAR(entered("Stopping"), fault_t, 0.0015)
        << "the supervisor starts stopping in the cycle of the fault";
    EXPECT_GT(entered("Stopped"), 0.0);
    EXPECT_LE(entered("Stopped") - fault_t, kControlledStopS);
    EXPECT_EQ(r.final_state, supervisor::State::stopped) << r.summary_text;
    EXPECT_EQ(outcome(), "stopped");
    EXPECT_FALSE(timeline_.f20_t) << "a category-1 stop needs no emergency stop";
    expect_cell_at_rest();
  }

  // A category-0 ending: the fault latched within `bound_ms` of the cause, Aborting in that cycle,
  // the SCU emulator holding an emergency stop (F20) within `f20_ms` of the fault, Aborted, the axes
  // at rest and the journal saying so.
  void expect_immediate_stop(const runtime::RunResult& r, const std::string& rule, double bound_ms,
                             double f20_ms) {
    report(rule, bound_ms);
    ASSERT_TRUE(timeline_.cause_t) << "the cause was never injected";
    const auto f = fault(rule);
    ASSERT_FALSE(f.is_null()) << "no fault event for " << rule << "\n" << r.summary_text;
    EXPECT_EQ(f["category"], 0);
    EXPECT_GE(reaction_ms(rule), 0.0);
    EXPECT_LE(reaction_ms(rule), bound_ms);
    const double fault_t = f["t"].get<double>();
    EXPECT_NEAR(entered("Aborting"), fault_t, 0.0015) << "the supervisor aborts in the cycle of the fault";
    ASSERT_TRUE(timeline_.f20_t) << "the SCU never saw the emergency stop";
    std::cout << "  [" << rule << "] F20 at the SCU " << (*timeline_.f20_t - fault_t) * 1000.0
              << " ms after the fault, Aborted after " << (entered("Aborted") - fault_t) * 1000.0 << " ms\n";
    EXPECT_LE((*timeline_.f20_t - fault_t) * 1000.0, f20_ms);
    EXPECT_EQ(r.final_state, supervisor::State::aborted) << r.summary_text;
    EXPECT_EQ(outcome(), "aborted");
    expect_axes_at_rest();
  }
};

// The F20 goes ahead of everything queued, after the telegram on the line (the longest SCU reply,
// 11 ms) and its own transmission.
constexpr double kEmergencyStopMs = 30.0;

TEST_F(MonitorRule, PositionLimit) {
  // The cell's travel shrinks below the recipe's target after the recipe was validated (a fixture
  // mounted in the way): x must not pass 50 mm (+0.5 mm margin) by the encoder.
  cell_.axes[0].max_mm = 50.0;
  const auto r = run_with([](double, runtime::CellRun& run) {
    return run.emulators()->scu()->actuator(1).true_position_mm() > 50.5;
  });
  expect_controlled_stop(r, "position_limit", kEncoderDataMs);
  // Past the limit by what 10 mm/s covers in the reaction time and the 40 mm/s² ramp's 1.25 mm.
  EXPECT_LT(run_->state().axes[0].encoder_mm, 50.5 + 10.0 * kEncoderDataMs / 1000.0 + 1.25);
}

TEST_F(MonitorRule, Overspeed) {
  // The move runs at 10 mm/s; the cell allows 8 mm/s by the encoder.
  cell_.limits.overspeed_mm_s = 8.0;
  const auto r = run_with([](double, runtime::CellRun& run) {
    return std::abs(run.emulators()->scu()->actuator(1).velocity_mm_s()) > 8.0;
  });
  // The encoder's velocity is a difference over its 10 ms time base, then the exchange.
  expect_controlled_stop(r, "overspeed", kEncoderDataMs);
}

// True once the plant itself disagrees: the SCU's sensor against what the encoder's shaft reads. The
// encoder's reading on the wire is one exchange (17 ms) old, 0.17 mm at 10 mm/s: against a fresh SCU
// position the monitor sees the disagreement that much early, so the cause counts from there.
bool plant_disagrees(runtime::CellRun& run, const config::CellConfig& cell) {
  auto* e = run.emulators();
  const double scu_mm = e->scu()->actuator(1).position_mm();
  const double encoder_mm = e->shaft()->revolutions() * e->shaft()->params().mm_per_revolution;
  const double encoder_lag_mm = 10.0 * 0.025;
  return std::abs(scu_mm - encoder_mm) > cell.limits.disagreement_mm - encoder_lag_mm;
}

TEST_F(MonitorRule, DisagreementFromShaftSlip) {
  // The encoder's coupling slips 5 %: SCU and encoder part by 2 mm after 40 mm of travel.
  emulators().plant.encoder_slip = 0.05;
  const auto r = run_with([this](double, runtime::CellRun& run) { return plant_disagrees(run, cell_); });
  expect_controlled_stop(r, "disagreement", kDisagreementMs);
}

TEST_F(MonitorRule, DisagreementFromScaleError) {
  // The SCU's position sensor of x reads 5 % long (the shipped plant: 0.2 %).
  emulators().scu->actuators[0].physics.scale_error = 0.05;
  const auto r = run_with([this](double, runtime::CellRun& run) { return plant_disagrees(run, cell_); });
  expect_controlled_stop(r, "disagreement", kDisagreementMs);
}

TEST_F(MonitorRule, EncoderNotReadyFromPositionError) {
  // A position-error alarm drops the Ready status bit in the cyclic data.
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->encoder()->set_alarm(encoder::alarm::position_error, true);
    return true;
  });
  expect_controlled_stop(r, "encoder_not_ready", kEncoderDataMs);
}

TEST_F(MonitorRule, EncoderAlarm) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->encoder()->set_alarm(encoder::alarm::supply_voltage, true);
    return true;
  });
  expect_controlled_stop(r, "encoder_alarm", kEncoderDiagnosisMs);
  EXPECT_TRUE(fault("encoder_not_ready").is_null()) << "a supply-voltage alarm leaves the Ready bit";
}

TEST_F(MonitorRule, EncoderLimitSwitch) {
  // The encoder's own upper limit switch at 30 mm (2048 counts per mm: 8192 steps per 4 mm turn).
  auto& p = cell_.encoder->session.parameters;
  p.upper_limit_enabled = true;
  p.upper_limit = 30 * 2048;
  const auto r = run_with([](double, runtime::CellRun& run) {
    return run.emulators()->scu()->actuator(1).true_position_mm() > 30.0;
  });
  expect_controlled_stop(r, "encoder_limit_switch", kEncoderDataMs);
}

TEST_F(MonitorRule, EncoderDiagnosis) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->encoder()->set_warning(encoder::warning::temperature_exceeded, true);
    return true;
  });
  expect_controlled_stop(r, "encoder_diagnosis", kEncoderDiagnosisMs);
}

TEST_F(MonitorRule, SpindleFault) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->spindle()->inject_fault(40);
    return true;
  });
  expect_controlled_stop(r, "spindle_fault", kSpindleStatusMs);
  EXPECT_NE(fault("spindle_fault")["detail"].get<std::string>().find("40"), std::string::npos);
}

TEST_F(MonitorRule, SpindleTemperature) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->spindle()->set_over_temperature(true);
    return true;
  });
  expect_controlled_stop(r, "spindle_temperature", kSpindleStatusMs);
}

TEST_F(MonitorRule, SpindleFrequencyAboveTheCell) {
  // The recipe asks for 400 Hz (validated against the shipped 800 Hz); the cell now allows 300 Hz:
  // the run-up passes 305 Hz (limit + tolerance) and the monitor stops the cell.
  cell_.limits.spindle_max_hz = 300.0;
  const auto r = run_with([this](double, runtime::CellRun& run) {
    return std::abs(run.emulators()->spindle()->motor().frequency_hz()) >
           cell_.limits.spindle_max_hz + cell_.limits.spindle_tolerance_hz;
  });
  expect_controlled_stop(r, "spindle_frequency", kSpindleValuesMs);
}

TEST_F(MonitorRule, SpindleFrequencyOffTheSetPoint) {
  // The motor sags to 380 Hz under load while the converter is set to 400 Hz (a plant disturbance).
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->spindle()->motor().run(380.0, true);
    return true;
  });
  // Judged only on a settled reading: 50 ms of ramp, then at speed for two value polls and a reply
  // time (600 ms), the next value poll (250 ms).
  expect_controlled_stop(r, "spindle_frequency", 950.0);
}

TEST_F(MonitorRule, ScuActuatorFault) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->scu()->inject_actuator_fault(1);
    return true;
  });
  expect_controlled_stop(r, "scu_error", kScuReplyMs);
}

TEST_F(MonitorRule, ScuOverCurrent) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->scu()->inject_over_current();
    return true;
  });
  expect_controlled_stop(r, "scu_error", kScuReplyMs);
}

TEST_F(MonitorRule, LinkSilentScuDropsReplies) {
  // The SCU carries out what it is told but its replies are lost from now on.
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->scu()->drop_next_replies(1'000'000);
    return true;
  });
  // Silent past 300 ms (link_silence_ms), counted from its last good reply (up to 100 ms earlier).
  // The F20 waits only for the request in flight to time out (its retries come after the stop).
  const auto& scu = cell_.scu->session;
  const double f20_ms = std::chrono::duration<double, std::milli>(scu.reply_timeout).count() + 30.0;
  expect_immediate_stop(r, "link_silent", 330.0, f20_ms);
  expect_cell_at_rest();  // the F20 got through (only the replies are lost), the spindle is reachable
  // Aborted once the SCU session gives the link up (link_fault_after_ms, judged at a reply time-out),
  // not after the 30 s stop time-out.
  EXPECT_LE(entered("Aborted") - fault("link_silent")["t"].get<double>(), 1.0 + 0.15);
}

TEST_F(MonitorRule, LinkSilentSpindle) {
  // A dead converter: it answers nothing and carries out nothing.
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->spindle()->set_silent(true);
    return true;
  });
  expect_immediate_stop(r, "link_silent", 330.0, kEmergencyStopMs);
}

TEST_F(MonitorRule, EncoderSilentIsNotReadyThenLinkSilent) {
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->encoder()->set_silent(true);
    return true;
  });
  // The master gives the slave up after lost_after_ms (100 ms) without a good reply: the encoder
  // left data exchange (category 1) and its session is no longer active — the link is lost
  // (category 0, which wins), in the same cycle.
  const auto not_ready = fault("encoder_not_ready");
  ASSERT_FALSE(not_ready.is_null()) << r.summary_text;
  EXPECT_EQ(not_ready["category"], 1);
  report("encoder_not_ready", 100.0 + kEncoderDataMs);
  EXPECT_LE(reaction_ms("encoder_not_ready"), 100.0 + kEncoderDataMs);
  expect_immediate_stop(r, "link_silent", 100.0 + kEncoderDataMs, kEmergencyStopMs);
  expect_cell_at_rest();
}

TEST_F(MonitorRule, OperatorStopHoldsThenStop) {
  // Ctrl-C once: the operator stop, category 2 — the axes come to a controlled stop and hold, the
  // spindle keeps running. A stop command then ends the run.
  std::optional<double> held_at;
  std::array<double, 3> held_mm{};  // by actuator number
  double max_drift_mm = 0.0;
  // The slowest the spindle turned at any cycle while Held: a restart or a ramp-down would show.
  double spindle_min_hz_held = std::numeric_limits<double>::infinity();
  const auto r = run_with(
      [this](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        interrupt_.store(true);
        return true;
      },
      [&](double t, runtime::CellRun& run) {
        if (run.supervisor().state() != supervisor::State::held) return;
        auto* scu = run.emulators()->scu();
        if (!held_at) {
          held_at = t;
          held_mm = {0.0, scu->actuator(1).true_position_mm(), scu->actuator(2).true_position_mm()};
        }
        for (int a = 1; a <= 2; ++a)
          max_drift_mm = std::max(max_drift_mm, std::abs(scu->actuator(a).true_position_mm() -
                                                         held_mm[static_cast<std::size_t>(a)]));
        spindle_min_hz_held =
            std::min(spindle_min_hz_held, std::abs(run.emulators()->spindle()->motor().frequency_hz()));
        if (t - *held_at > 1.0) run.request(supervisor::Command::stop);
      });
  report("operator_stop", 2.0);
  const auto f = fault("operator_stop");
  ASSERT_FALSE(f.is_null()) << r.summary_text;
  EXPECT_EQ(f["category"], 2);
  EXPECT_LE(reaction_ms("operator_stop"), 2.0) << "taken in the next cycle";
  EXPECT_NEAR(entered("Holding"), f["t"].get<double>(), 0.0015);
  ASSERT_TRUE(held_at) << r.summary_text;
  // Held once the axes are still: the 10 mm/s ramp takes 0.25 s, the SCU reports within 100 ms.
  EXPECT_LE(*held_at - f["t"].get<double>(), 0.25 + kScuReplyMs / 1000.0 + 0.05);
  EXPECT_LE(max_drift_mm, 0.01) << "the axes stay where they stopped while held";
  EXPECT_NEAR(spindle_min_hz_held, 400.0, 1.0) << "category 2 keeps the spindle running all the time held";
  EXPECT_FALSE(timeline_.f20_t);
  EXPECT_EQ(r.final_state, supervisor::State::stopped) << r.summary_text;
  EXPECT_EQ(outcome(), "stopped");
  expect_cell_at_rest();
}

TEST_F(MonitorRule, EmergencyStopByInterruptTwice) {
  // Ctrl-C twice: the first is the operator stop (hold), the second the emergency stop, category 0.
  const auto r = run_with(
      [this](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        interrupt_.store(true);
        return true;
      },
      [this](double t, runtime::CellRun& run) {
        if (t - *timeline_.cause_t > 0.05 && !run.monitor().latch(monitor::Rule::emergency_stop).active)
          interrupt_.store(true);
      });
  EXPECT_EQ(fault("operator_stop")["category"], 2);
  // Measured from the first interrupt: the second came 50 ms later and was taken in the next cycle.
  expect_immediate_stop(r, "emergency_stop", 52.0, kEmergencyStopMs);
  EXPECT_TRUE(r.interrupted);
  expect_cell_at_rest();
}

TEST_F(MonitorRule, AbortCommandIsAnImmediateStop) {
  // The operator's abort goes to the supervisor directly (no monitor latch): Aborting, F20 at the SCU.
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.request(supervisor::Command::abort);
    return true;
  });
  ASSERT_TRUE(timeline_.cause_t);
  const auto commands = events("command");
  ASSERT_FALSE(commands.empty());
  EXPECT_EQ(commands.back()["command"], "abort");
  EXPECT_LE(entered("Aborting") - *timeline_.cause_t, 0.0015);
  ASSERT_TRUE(timeline_.f20_t);
  EXPECT_LE((*timeline_.f20_t - *timeline_.cause_t) * 1000.0, kEmergencyStopMs);
  EXPECT_EQ(r.final_state, supervisor::State::aborted) << r.summary_text;
  EXPECT_EQ(outcome(), "aborted");
  EXPECT_TRUE(events("fault").empty());
  expect_cell_at_rest();
}

// The category comes from the config's `stops:`, not from the rule.
TEST_F(MonitorRule, ConfiguredCategoryTwoHolds) {
  cell_.stops.fault = config::StopCategory::controlled_hold;
  const auto r = run_with(
      [](double, runtime::CellRun& run) {
        if (!in_traverse_past(run, 20.0)) return false;
        run.emulators()->encoder()->set_warning(encoder::warning::battery_charge, true);
        return true;
      },
      [](double, runtime::CellRun& run) {
        if (run.supervisor().state() == supervisor::State::held) run.request(supervisor::Command::stop);
      });
  report("encoder_diagnosis", kEncoderDiagnosisMs);
  EXPECT_EQ(fault("encoder_diagnosis")["category"], 2);
  EXPECT_LE(reaction_ms("encoder_diagnosis"), kEncoderDiagnosisMs);
  EXPECT_GT(entered("Held"), 0.0);
  EXPECT_EQ(r.final_state, supervisor::State::stopped) << r.summary_text;
  expect_cell_at_rest();
}

TEST_F(MonitorRule, ConfiguredCategoryZeroAborts) {
  cell_.stops.fault = config::StopCategory::immediate;
  const auto r = run_with([](double, runtime::CellRun& run) {
    if (!in_traverse_past(run, 20.0)) return false;
    run.emulators()->spindle()->inject_fault(40);
    return true;
  });
  expect_immediate_stop(r, "spindle_fault", kSpindleStatusMs, kEmergencyStopMs);
  expect_cell_at_rest();
}

}  // namespace
}  // namespace cellctl::testing
