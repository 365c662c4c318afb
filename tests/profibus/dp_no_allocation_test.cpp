// The cyclic path allocates nothing: data exchange, a DH diagnosis read, a lost slave with restart
// and its return, Data_Exchange replies of the wrong length, all polled without one heap allocation
// on either side (after construction).

#include <gtest/gtest.h>

#include <chrono>

#include "bus_fixture.hpp"
#include "support/allocation_counter.hpp"

namespace cellctl::profibus::testing {
namespace {

using std::chrono::milliseconds;

TEST(DpNoAllocation, PollNeverAllocates) {
  Bus bus;
  bus.behaviour.ext.reserve(16);
  bus.behaviour.last_outputs.reserve(16);
  bus.behaviour.last_user_prm.reserve(16);
  bus.behaviour.left.reserve(16);
  bus.master.activate(bus.now());
  ASSERT_TRUE(bus.run_until([&] { return bus.in_data_exchange(); }, milliseconds(10)));

  const std::size_t before = cellctl::testing::allocation_count();
  auto steps_for = [&](link::Duration span) {
    const auto until = bus.now() + span;
    while (bus.now() < until) bus.step();
  };
  steps_for(milliseconds(10));
  bus.behaviour.pending = true;  // DH → Slave_Diag
  steps_for(milliseconds(5));
  bus.slave.set_silent(true);  // lost → restart with a reason
  steps_for(milliseconds(40));
  bus.slave.set_silent(false);
  steps_for(milliseconds(20));
  bus.behaviour.input_length = 6;  // replies of the wrong length → restart with a formatted reason
  steps_for(milliseconds(10));
  bus.behaviour.input_length = 8;
  steps_for(milliseconds(20));
  const std::size_t after = cellctl::testing::allocation_count();

  EXPECT_EQ(after, before);
  EXPECT_GE(bus.master.stats().bad_inputs, 1u);
  EXPECT_EQ(bus.master.stats().lost, 1u);
  EXPECT_GE(bus.master.stats().startups, 2u);
  EXPECT_TRUE(bus.in_data_exchange());
}

}  // namespace
}  // namespace cellctl::profibus::testing
