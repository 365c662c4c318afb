// The data list's sizes and groups, and the decoded status and error flags.

#include "scu/data_list.hpp"

#include <gtest/gtest.h>

#include <string>

#include "scu/status_flags.hpp"

namespace cellctl::scu {
namespace {

TEST(ScuDataList, SizesOfElementsAndGroups) {
  EXPECT_EQ(value_size(0x0001), 31u);
  EXPECT_EQ(value_size(0x0002), 36u);
  EXPECT_EQ(value_size(0x0011), 4u);
  EXPECT_EQ(value_size(0x0010), 24u) << "RG 0x0010 returns all six positions";
  EXPECT_EQ(value_size(0x0170), 6u);
  EXPECT_EQ(value_size(0x0020), 1u) << "0x0020 is an element, not a group";
  EXPECT_EQ(value_size(0x0080), 7u * 4u) << "A1..A6 and the total over-current count";
  EXPECT_EQ(value_size(0x00C0), 1u);
  EXPECT_EQ(value_size(0x0160), 2u + 2u + 1u + 1u);
  EXPECT_EQ(value_size(0x1010), 24u);
  EXPECT_EQ(value_size(0x2001), 104u);
  EXPECT_EQ(value_size(0x3001), 24u);
  EXPECT_EQ(value_size(0x3010), 20u);
  EXPECT_EQ(value_size(0x3020), 24u);
  EXPECT_EQ(value_size(0x0017), 0u);
  EXPECT_EQ(value_size(0x4000), 0u);
  EXPECT_EQ(elements_of(0x0010).front().id, 0x0011);
  EXPECT_EQ(elements_of(0x0010).back().id, 0x0016);
  EXPECT_TRUE(is_remote_data(0x3021));
  EXPECT_FALSE(is_remote_data(0x0171));
}

TEST(ScuStatusFlags, Status1BitsFromTheManual) {
  const auto s = Status1::from_byte(0x31);  // the notes' example reply: present, motion active, in position
  EXPECT_TRUE(s.present);
  EXPECT_TRUE(s.motion_active);
  EXPECT_TRUE(s.in_position);
  EXPECT_FALSE(s.out_position);
  EXPECT_FALSE(s.limit_signal);
  EXPECT_EQ(s.to_byte(), 0x31);
  for (unsigned b = 0; b < 256; ++b) EXPECT_EQ(Status1::from_byte(static_cast<std::uint8_t>(b)).to_byte(), b);
  EXPECT_EQ(Status2::from_byte(0x07).to_byte(), 0x07);
  EXPECT_TRUE(Status2::from_byte(0x01).initialized);
}

TEST(ScuStatusFlags, ErrorBitsCountFromOne) {
  ErrorWord w(0x00200000u);  // bit 22 numbered from 1 = 1 << 21
  EXPECT_TRUE(w.remote_timeout());
  EXPECT_FALSE(w.position_difference());
  w.set(error_bit::actuator_fault(2));
  EXPECT_EQ(w.raw(), 0x00200000u | (1u << 15));
  EXPECT_TRUE(w.actuator_fault(2));
  EXPECT_TRUE(ErrorWord(1u << 13).over_current());
  std::string causes;
  w.for_each_cause([&](int bit, std::string_view cause) {
    causes += std::to_string(bit) + ":" + std::string(cause) + ";";
  });
  EXPECT_EQ(causes, "16:actuator 2 fault;22:remote communication time-out (watchdog);");
}

}  // namespace
}  // namespace cellctl::scu
