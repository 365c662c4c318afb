// The session's receive() and transmit() allocate nothing after construction — data exchange, a lost slave
// with its restart during a handshake, and the start-up refusals whose reasons are composed in the cycle.

#include <gtest/gtest.h>

#include <chrono>

#include "session_rig.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::encoder::testing {
namespace {

using link::Lifecycle;

// Only the session's polls count; the first reference to allocation_count is made here, not in poll.
void count_session_allocations(Rig& rig) {
  rig.allocation_count = [] { return cellctl::testing::allocation_count(); };
}

TEST(EncoderNoAllocation, DataExchangeAndALostSlaveDuringAPreset) {
  Rig rig;
  count_session_allocations(rig);
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return rig.exchanging(); }, 200ms)) << s.fault_reason();
  ASSERT_TRUE(s.preset(1000));
  rig.emulator->set_silent(true);  // lost while the handshake waits: aborted, then a restart
  ASSERT_TRUE(rig.run_until([&] { return !s.snapshot().data_exchange; }, 200ms));
  rig.run_for(30ms);
  rig.emulator->set_silent(false);
  const auto before = s.snapshot().exchanges;
  ASSERT_TRUE(rig.run_until([&] { return s.snapshot().data_exchange && s.snapshot().exchanges > before + 2; },
                            500ms));

  EXPECT_EQ(rig.session_poll_allocations, 0u);
  EXPECT_EQ(s.snapshot().command.phase, Handshake::Phase::failed);
  EXPECT_EQ(s.snapshot().command.failure, "data exchange lost during the handshake");
}

TEST(EncoderNoAllocation, SlavePrmFaultReasonIsComposedWithoutAllocating) {
  Rig rig;
  count_session_allocations(rig);
  // Passes the local check for a 16-bit singleturn; the emulated 13-bit encoder refuses it.
  rig.session_config.physical = PhysicalResolution{65536, 512};
  rig.session_config.parameters.scaling = true;
  rig.session_config.parameters.measuring_units = 16384;
  rig.session_config.parameters.total_range = 16384 * 64;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return s.lifecycle() == Lifecycle::fault; }, 200ms));

  EXPECT_EQ(rig.session_poll_allocations, 0u);
  EXPECT_EQ(s.snapshot().startup_fault, profibus::StartupFault::Kind::prm_fault);
  EXPECT_NE(s.fault_reason().find("pass the local check for 65536 steps × 512 revolutions; the encoder "
                                  "reports 8192 × 4096"),
            std::string::npos)
      << s.fault_reason();
}

TEST(EncoderNoAllocation, SlaveCfgFaultReasonIsComposedWithoutAllocating) {
  Rig rig(Functionality::scancon22);
  count_session_allocations(rig);
  // Without Status Bits is a Scancon 3.0 parameter: the encoder refuses it with the 2.2 configuration.
  rig.session_config.parameters.without_status_bits = true;
  Session& s = rig.start();
  ASSERT_TRUE(rig.run_until([&] { return s.lifecycle() == Lifecycle::fault; }, 200ms));

  EXPECT_EQ(rig.session_poll_allocations, 0u);
  EXPECT_NE(s.fault_reason().find("Cfg_Fault"), std::string::npos) << s.fault_reason();
  EXPECT_NE(s.fault_reason().find("the encoder refused configuration scancon2.2"), std::string::npos)
      << s.fault_reason();
}

}  // namespace
}  // namespace cellctl::encoder::testing
