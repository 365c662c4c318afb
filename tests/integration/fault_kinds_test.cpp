// Every kind of rehearsed fault (cellctl run --fault) on every device, over SimLinks in virtual time:
// the fault reaches the device's session the way it is meant to — through the FaultInjectingLink
// under the session, or through the emulator's own fault — and the session shows it in the cell
// state; the journal names the injected fault from its start to its end.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "fault_run.hpp"
#include "runtime/fault_spec.hpp"

namespace cellctl::testing {
namespace {

using namespace std::chrono_literals;

// The traverse recipe of fault_run.hpp: the fault comes while the axes move with the spindle on.
constexpr double kAt = 1.5;       // s after the start: the traverse runs, the spindle at speed
constexpr double kLasting = 1.0;  // s

// What the cell state showed of one device while the fault was on, and before it.
struct Seen {
  link::Duration silent_before{};  // longest time without a good reply before the fault
  link::Duration silent_during{};
  bool session_fault = false;  // the session gave up on its link
  bool link_inactive = false;  // the session left its active state
  bool scu_actuator_fault = false;
  std::uint8_t spindle_fault = 0;
  bool encoder_alarm = false;
  bool encoder_left = false;  // left data exchange
};

struct Case {
  cell::Device device;
  std::string kind;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << cell::to_string(c.device) << ":" << c.kind;
}

class FaultKinds : public RunFixture, public ::testing::WithParamInterface<Case> {
 protected:
  Seen run_case(const std::string& spec_text) {
    auto parsed = runtime::parse_fault_spec(spec_text);
    EXPECT_TRUE(std::holds_alternative<runtime::FaultSpec>(parsed)) << spec_text;
    faults_ = {std::get<runtime::FaultSpec>(parsed)};
    load_recipe_text(kTraverseRecipe);
    auto& run = make_run();
    const auto d = static_cast<std::size_t>(GetParam().device);
    Seen seen;
    run.on_cycle([&](double t, runtime::CellRun& r) {
      const auto& s = r.state();
      const auto& l = s.links[d];
      if (t < kAt) {
        if (t > 1.0) seen.silent_before = std::max(seen.silent_before, l.silent_for);  // after start-up
        return;
      }
      if (t >= kAt + kLasting) return;
      seen.silent_during = std::max(seen.silent_during, l.silent_for);
      seen.session_fault |= l.fault;
      seen.link_inactive |= !l.active;
      for (std::size_t a = 0; a < s.axis_count; ++a) seen.scu_actuator_fault |= s.axes[a].actuator_fault;
      if (s.spindle.fault) seen.spindle_fault = s.spindle.fault_number;
      seen.encoder_alarm |= s.encoder.alarm;
      seen.encoder_left |= !s.encoder.data_exchange;
    });
    result_ = go();
    return seen;
  }

  // The journal's first monitor fault after the injection, as "rule: detail" (empty: none).
  std::string first_fault() const {
    const auto f = events("fault");
    return f.empty() ? std::string()
                     : f[0]["rule"].get<std::string>() + ": " + f[0]["detail"].get<std::string>();
  }
  double first_fault_after_ms() const {
    const auto f = events("fault");
    return f.empty() ? 1e9 : (f[0]["t"].get<double>() - kAt) * 1000.0;
  }

  // The journal names the fault when it began and when it ended — at its end, or with the run when
  // the run (stopped by it) was over first.
  void expect_journal_names(const std::string& spec_text) {
    const auto began = events("fault_injected");
    ASSERT_EQ(began.size(), 1u);
    EXPECT_EQ(began[0]["spec"], spec_text);
    EXPECT_EQ(began[0]["device"], cell::to_string(GetParam().device));
    EXPECT_NEAR(began[0]["t"].get<double>(), kAt, 0.0015);
    const auto ended = events("fault_injection_ended");
    ASSERT_EQ(ended.size(), 1u);
    EXPECT_EQ(ended[0]["spec"], spec_text);
    const auto run_end = events("run_ended");
    ASSERT_EQ(run_end.size(), 1u);
    if (ended[0].value("still_active", false))
      EXPECT_LT(ended[0]["t"].get<double>(), kAt + kLasting);
    else
      EXPECT_NEAR(ended[0]["t"].get<double>(), kAt + kLasting, 0.0015);
  }

  runtime::RunResult result_;
};

std::string spec_of(const Case& c) {
  return std::string(cell::to_string(c.device)) + ":" + c.kind + "@" + std::to_string(kAt).substr(0, 3) +
         "+" + std::to_string(kLasting).substr(0, 3);
}

std::string name_of(const ::testing::TestParamInfo<Case>& info) {
  std::string kind = info.param.kind;
  std::replace(kind.begin(), kind.end(), '=', '_');
  return std::string(cell::to_string(info.param.device)) + "_" + kind;
}

TEST_P(FaultKinds, ShowTheirEffectOnTheSession) {
  const Case c = GetParam();
  const std::string spec = spec_of(c);
  const Seen seen = run_case(spec);
  const std::string fault = first_fault();
  const double after_ms = first_fault_after_ms();
  std::cout << "  [" << spec << "] first fault after " << after_ms << " ms: " << fault << "; silent "
            << link::to_milliseconds(seen.silent_before) << " ms before, up to "
            << link::to_milliseconds(seen.silent_during) << " ms during\n";
  const bool encoder = c.device == cell::Device::encoder;
  const std::string device = cell::to_string(c.device);

  if (c.kind == "garbage") {
    // Noise damages telegrams, not all of them: the session loses replies (retries, time-outs) and
    // its link goes quiet for longer than ever before; whether that ends the run is the session's
    // and the monitor's call (at 1 s of noise the SCU's link stays just under the 300 ms limit).
    EXPECT_GE(seen.silent_during, seen.silent_before + 100ms);
  } else if (c.kind == "silent" || c.kind == "corrupt" || c.kind == "delay=400") {
    // No good reply gets through (or none in time): the session's link goes silent and the monitor
    // stops the cell for the link, naming the device.
    if (encoder) {
      EXPECT_TRUE(seen.encoder_left) << "the DP master lost the slave";
    } else {
      EXPECT_GE(seen.silent_during, 300ms);
    }
    EXPECT_NE(fault.find(device), std::string::npos) << fault;
    EXPECT_LT(after_ms, 700.0) << fault;
  } else if (c.kind == "disconnect") {
    // The port reports itself gone: SCU and spindle sessions fault at once; the DP master treats it
    // as a slave that stopped answering and loses it after lost_slave_time.
    if (encoder) {
      EXPECT_TRUE(seen.encoder_left);
      EXPECT_LT(after_ms, 150.0) << fault;
    } else {
      EXPECT_TRUE(seen.session_fault);
      EXPECT_LT(after_ms, 5.0) << fault;
    }
    EXPECT_NE(fault.find(device), std::string::npos) << fault;
  } else if (c.kind == "delay=50") {
    // Below every time-out: replies come late, nothing faults, the recipe completes.
    EXPECT_GE(seen.silent_during, seen.silent_before + 40ms) << "the late replies are seen late";
    EXPECT_EQ(fault, "");
    EXPECT_EQ(result_.final_state, supervisor::State::complete);
  } else if (c.kind == "error") {
    switch (c.device) {
      case cell::Device::scu:
        EXPECT_TRUE(seen.scu_actuator_fault);
        break;
      case cell::Device::spindle:
        EXPECT_EQ(seen.spindle_fault, 31) << "motor over-temperature";
        break;
      case cell::Device::encoder:
        EXPECT_TRUE(seen.encoder_alarm);
        break;
    }
    EXPECT_FALSE(seen.session_fault) << "the link itself is fine";
    EXPECT_LT(after_ms, 100.0) << fault;
  }
  expect_journal_names(spec);
  if (c.kind != "delay=50" && c.kind != "garbage") {
    EXPECT_NE(result_.final_state, supervisor::State::complete);
  }
}

std::vector<Case> all_cases() {
  std::vector<Case> out;
  for (const auto d : {cell::Device::scu, cell::Device::spindle, cell::Device::encoder})
    for (const char* k : {"silent", "disconnect", "corrupt", "garbage", "delay=50", "delay=400", "error"})
      out.push_back({d, k});
  return out;
}

INSTANTIATE_TEST_SUITE_P(EveryDevice, FaultKinds, ::testing::ValuesIn(all_cases()), name_of);

}  // namespace
}  // namespace cellctl::testing
