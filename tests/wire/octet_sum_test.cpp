#include "wire/octet_sum.hpp"

#include <gtest/gtest.h>

#include <array>

namespace cellctl::wire {
namespace {

TEST(OctetSum, IsTheSumWithItsCarriesDropped) {
  EXPECT_EQ(octet_sum({}), 0);
  // The FCS of an SD1 FDL_Status request, 10 05 02 49 50 16: DA 0x05 + SA 0x02 + FC 0x49 = 0x50.
  const std::array<std::uint8_t, 3> sd1{0x05, 0x02, 0x49};
  EXPECT_EQ(octet_sum(sd1), 0x50);
  // Carries are dropped, not folded back in (an end-around carry, as some checksums do, gives 0x03).
  const std::array<std::uint8_t, 3> carries{0xff, 0xff, 0x03};  // 0x201
  EXPECT_EQ(octet_sum(carries), 0x01);
}

}  // namespace
}  // namespace cellctl::wire
