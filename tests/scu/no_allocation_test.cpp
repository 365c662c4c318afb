// receive() and transmit() allocate nothing after construction — cyclic refresh, a move, and the link fault
// with its reason composed at the moment it happens — on session and emulator both.

#include <gtest/gtest.h>

#include <chrono>

#include "scu_rig.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::scu::testing {
namespace {

using namespace std::chrono_literals;
using link::Lifecycle;

TEST(ScuNoAllocation, CyclicExchangeAMoveAndALinkFault) {
  Rig rig(1);
  ASSERT_TRUE(rig.activate());

  const std::size_t before = cellctl::testing::allocation_count();
  const ActuatorTarget t[] = {{1, 40.0}};
  ASSERT_TRUE(rig.session.move_to(1, t, 10.0, true));
  rig.run_until(500ms, [] { return false; });
  rig.sim.set_cut(true);
  const bool faulted = rig.run_until(2s, [&] { return rig.session.lifecycle() == Lifecycle::fault; });
  const std::size_t after = cellctl::testing::allocation_count();

  ASSERT_TRUE(faulted);
  EXPECT_EQ(after, before);
  EXPECT_GT(rig.emulator.actuator(1).position_mm(), 0.0) << "the move ran";
  EXPECT_NE(rig.session.fault_reason().find("silent for"), std::string::npos) << rig.session.fault_reason();
}

TEST(ScuNoAllocation, AnUnansweredActivationFaultsWithoutAllocating) {
  Rig rig(1);
  const std::size_t before = cellctl::testing::allocation_count();
  rig.session.activate(rig.clock.now());
  rig.emulator.drop_next_replies(100);
  const bool faulted = rig.run_until(2s, [&] { return rig.session.lifecycle() == Lifecycle::fault; });
  const std::size_t after = cellctl::testing::allocation_count();

  ASSERT_TRUE(faulted);
  EXPECT_EQ(after, before);
  EXPECT_NE(rig.session.fault_reason().find("attempts"), std::string::npos) << rig.session.fault_reason();
}

}  // namespace
}  // namespace cellctl::scu::testing
