// The safe-stop after a fault, in virtual time over SimLinks with faults put on the line on purpose
// (runtime/safe_stop.hpp): the loop keeps cycling after the run has ended until every device's stop
// is confirmed (observed) or bounded by its own protection, and the summary says which, per device.
// The traverse recipe of fault_run.hpp: the fault comes at 1.5 s while x and z move and the spindle
// turns at 400 Hz.

#include <gtest/gtest.h>

#include <string>

#include "fault_run.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::testing {
namespace {

constexpr double kAt = 1.5;

class SafeStop : public FaultRun {
 protected:
  runtime::RunResult run_faults(std::initializer_list<const char*> specs) {
    for (const auto* text : specs) {
      auto parsed = runtime::parse_fault_spec(text);
      EXPECT_TRUE(std::holds_alternative<runtime::FaultSpec>(parsed)) << text;
      faults_.push_back(std::get<runtime::FaultSpec>(parsed));
    }
    load_recipe_text(kTraverseRecipe);
    auto& run = make_run();
    run.on_cycle([this](double t, runtime::CellRun& r) {
      auto* scu = r.emulators()->scu();
      if (t >= kAt && scu->emergency_stop_active() && !f20_after_fault_) f20_after_fault_ = t;
      if (t >= kAt && !moving_at_fault_) moving_at_fault_ = scu->actuator(1).moving();
    });
    return go();
  }
  nlohmann::json summary() const {
    const auto s = events("summary");
    return s.size() == 1 ? s[0] : nlohmann::json();
  }
  std::string safe(const char* device) const { return summary()["devices"][device]["safe"]; }
  std::string evidence(const char* device) const { return summary()["devices"][device]["evidence"]; }

  std::optional<double> f20_after_fault_;
  std::optional<bool> moving_at_fault_;
};

TEST_F(SafeStop, ScuPortLostWhileMovingIsOpenedAgainAndTheStopConfirmed) {
  // The port is gone for 0.2 s: shorter than the SCU's 0.5 s communication time-out, so only the
  // program's own stop, sent after the port is back, stops the axes.
  const auto r = run_faults({"scu:disconnect@1.5+0.2"});
  ASSERT_TRUE(moving_at_fault_.value_or(false)) << "the fault must come while the axes move";
  EXPECT_EQ(safe("scu"), "observed") << evidence("scu");
  ASSERT_TRUE(f20_after_fault_) << "no F20 reached the SCU after its port came back";
  EXPECT_GE(*f20_after_fault_, kAt + 0.2);
  EXPECT_LT(*f20_after_fault_, kAt + 0.2 + 0.2) << "F20 within two reopen attempts of the port's return";
  EXPECT_NE(evidence("scu").find("port opened again 1 time(s)"), std::string::npos) << evidence("scu");
  EXPECT_NE(evidence("scu").find("last SCU positions"), std::string::npos) << evidence("scu");
  EXPECT_NE(evidence("scu").find("last measured x"), std::string::npos) << evidence("scu");
  expect_axes_at_rest();
  EXPECT_GT(r.duration_s, *f20_after_fault_) << "the run ended before the stop was confirmed";
  const auto ended = summary()["ended_by"];
  EXPECT_EQ(ended["kind"], "link");
  EXPECT_EQ(ended["device"], "scu");
  EXPECT_NE(ended["symptom"].get<std::string>().find("closed"), std::string::npos) << ended.dump();
  EXPECT_FALSE(r.any_unknown());
}

TEST_F(SafeStop, ScuPortLostForGoodIsBoundedByItsOwnTimeOutAndWatchedMeanwhile) {
  const auto r = run_faults({"scu:disconnect@1.5"});
  ASSERT_TRUE(moving_at_fault_.value_or(false));
  EXPECT_EQ(safe("scu"), "bounded") << evidence("scu");
  // Never before the SCU's communication time-out (0.5 s) plus the actuators' stopping time after
  // the last request that reached it (at most one keep-alive period before the port went).
  const double bound = kAt - 0.1 + 0.5 + link::to_seconds(cell_.scu->session.stopping_time);
  EXPECT_GE(r.duration_s, bound) << "cellctl ended before the SCU's own protection had surely acted";
  EXPECT_LT(r.duration_s, kAt + 0.5 + link::to_seconds(cell_.scu->session.stopping_time) + 0.2);
  expect_axes_at_rest();  // the emulated SCU's watchdog stopped them, as the manual says
  EXPECT_NE(evidence("scu").find("communication time-out"), std::string::npos) << evidence("scu");
  // The SCU's positions stopped arriving: named as the link, never as a disagreement with the encoder.
  EXPECT_TRUE(fault("disagreement").is_null()) << fault("disagreement").dump();
  EXPECT_EQ(summary()["ended_by"]["kind"], "link");
  EXPECT_NE(evidence("scu").find("attempt(s) refused"), std::string::npos) << "reopening never tried";
  // The encoder was watched to the end, after the axes had stopped.
  EXPECT_EQ(safe("encoder"), "observed") << evidence("encoder");
  const double measured = run_->emulators()->scu()->actuator(1).true_position_mm();
  EXPECT_NE(evidence("scu").find(fmt::format("last measured x {:.1f}", measured)), std::string::npos)
      << evidence("scu") << " (the axis stood at " << measured << " mm)";
  EXPECT_EQ(safe("spindle"), "observed") << evidence("spindle");
}

TEST_F(SafeStop, SpindleSilentThenBackGetsItsStopUntilStandstill) {
  const auto r = run_faults({"spindle:silent@1.5+2"});
  EXPECT_EQ(safe("spindle"), "observed") << evidence("spindle");
  EXPECT_TRUE(run_->emulators()->spindle()->motor().at_rest())
      << run_->emulators()->spindle()->motor().frequency_hz() << " Hz";
  // The line is back at 3.5 s; from 400 Hz the converter runs down at 400 Hz/s.
  EXPECT_GE(r.duration_s, kAt + 2.0 + 0.9) << "ended before the converter could report standstill";
  EXPECT_NE(evidence("spindle").find("STILLSTAND reported"), std::string::npos) << evidence("spindle");
  EXPECT_EQ(summary()["ended_by"]["device"], "spindle");
  EXPECT_FALSE(r.any_unknown());
}

TEST_F(SafeStop, SpindleNeverBackIsUnknownWithItsLastSetFrequency) {
  const auto r = run_faults({"spindle:silent@1.5"});
  EXPECT_EQ(safe("spindle"), "unknown") << evidence("spindle");
  EXPECT_TRUE(r.any_unknown());
  EXPECT_NE(evidence("spindle").find("may still be turning at 400 Hz"), std::string::npos)
      << evidence("spindle");
  // The converter has no watchdog: it is still turning, which is why this must be said.
  EXPECT_GT(run_->emulators()->spindle()->motor().frequency_hz(), 300.0);
  EXPECT_EQ(safe("scu"), "observed") << evidence("scu");
  expect_axes_at_rest();
}

TEST_F(SafeStop, EncoderLinkLostIsNamedAsTheLinkAndBounded) {
  const auto r = run_faults({"encoder:disconnect@1.5"});
  EXPECT_EQ(safe("encoder"), "bounded") << evidence("encoder");
  EXPECT_EQ(safe("scu"), "observed") << evidence("scu");
  EXPECT_EQ(safe("spindle"), "observed") << evidence("spindle");
  const auto ended = summary()["ended_by"];
  EXPECT_EQ(ended["kind"], "link") << ended.dump();
  EXPECT_EQ(ended["device"], "encoder") << ended.dump();
  EXPECT_NEAR(ended["since_s"].get<double>(), kAt, 0.05) << ended.dump();
  EXPECT_TRUE(fault("disagreement").is_null()) << fault("disagreement").dump();
  EXPECT_TRUE(fault("following_error").is_null()) << fault("following_error").dump();
  EXPECT_FALSE(r.any_unknown());
}

TEST_F(SafeStop, HealthyRunEndsWithEveryDeviceObserved) {
  load_recipe_text(kCreepRecipe);
  make_run();
  const auto r = go();
  ASSERT_EQ(r.final_state, supervisor::State::complete);
  for (const auto* d : {"scu", "spindle", "encoder"})
    EXPECT_EQ(safe(d), "observed") << d << ": " << evidence(d);
  EXPECT_FALSE(summary().contains("ended_by"));
}

}  // namespace
}  // namespace cellctl::testing
