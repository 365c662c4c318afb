// The DP-V0 data units: standard diagnosis bits where the standard puts them, the Set_Prm standard
// octets, Global_Control and Set_Slave_Add — byte-exact and round trips, short input refused.

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "profibus/dp_diag.hpp"
#include "profibus/dp_services.hpp"
#include "wire/hex.hpp"

namespace cellctl::profibus {
namespace {

template <std::size_t N>
std::string hex(const std::array<std::uint8_t, N>& a, std::size_t n) {
  return wire::to_hex(std::span<const std::uint8_t>(a.data(), n));
}

TEST(DpDiag, FreshSlaveAwaitingParameters) {
  StandardDiag d;
  d.station_not_ready = true;
  d.prm_req = true;
  d.ident = 0x1234;
  std::array<std::uint8_t, 6> out{};
  ASSERT_EQ(encode(d, out), 6u);
  // Station_Not_Ready = octet 1 bit 1; Prm_Req = octet 2 bit 0 plus the fixed bit 2; no master.
  EXPECT_EQ(hex(out, 6), "02 05 00 ff 12 34");
  EXPECT_EQ(decode_standard_diag(out), d);
  EXPECT_FALSE(d.ready_for_data_exchange());
}

TEST(DpDiag, EveryBitInItsPlace) {
  StandardDiag d;
  d.station_non_existent = d.cfg_fault = d.ext_diag = d.not_supported = d.invalid_slave_response = true;
  d.prm_fault = d.master_lock = d.stat_diag = d.wd_on = d.freeze_mode = d.sync_mode = d.deactivated = true;
  d.ext_diag_overflow = true;
  d.master_address = 2;
  d.ident = 0xabcd;
  std::array<std::uint8_t, 6> out{};
  ASSERT_EQ(encode(d, out), 6u);
  EXPECT_EQ(hex(out, 6), "fd be 80 02 ab cd");
  EXPECT_EQ(decode_standard_diag(out), d);
}

TEST(DpDiag, ExtendedPartStaysRawAndShortRepliesAreRefused) {
  const auto bytes = *wire::parse_hex("00 0c 00 02 12 34 0a 01 02 03");
  const auto d = decode_diagnosis(bytes);
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->standard.wd_on);
  EXPECT_TRUE(d->standard.ready_for_data_exchange());
  EXPECT_EQ(wire::to_hex(d->extended.view()), "0a 01 02 03");
  EXPECT_FALSE(decode_diagnosis(std::span<const std::uint8_t>(bytes).first(5)));
}

TEST(DpDiag, ADiagnosisLongerThanADataUnitIsRefusedNotCut) {
  std::vector<std::uint8_t> bytes(kMaxData, 0x00);
  bytes[1] = 0x0c;
  ASSERT_TRUE(decode_diagnosis(bytes)) << "244 octets is the most a DP data unit carries";
  EXPECT_EQ(decode_diagnosis(bytes)->extended.size(), kMaxData - kStandardDiagSize);
  bytes.push_back(0x00);
  EXPECT_FALSE(decode_diagnosis(bytes))
      << "245 octets cannot be a whole Slave_Diag: cut, it would read as one";
}

TEST(DpServices, PrmStandardOctets) {
  PrmStandard p;
  p.wd_fact_1 = 10;
  p.wd_fact_2 = 5;
  p.min_tsdr_bits = 11;
  p.ident = 0x1234;
  p.group = 0x01;
  p.freeze_req = true;
  std::array<std::uint8_t, 7> out{};
  ASSERT_EQ(encode(p, out), 7u);
  // Lock_Req (bit 7) + Freeze_Req (bit 4) + WD_On (bit 3).
  EXPECT_EQ(hex(out, 7), "98 0a 05 0b 12 34 01");
  EXPECT_EQ(decode_prm_standard(out), p);
  EXPECT_FALSE(decode_prm_standard(std::span<const std::uint8_t>(out).first(6)));
}

TEST(DpServices, GlobalControlAndSetSlaveAdd) {
  GlobalControl gc{
      static_cast<std::uint8_t>(GlobalCommand::freeze) | static_cast<std::uint8_t>(GlobalCommand::sync),
      0x03};
  std::array<std::uint8_t, 2> g{};
  ASSERT_EQ(encode(gc, g), 2u);
  EXPECT_EQ(hex(g, 2), "28 03");
  const auto back = decode_global_control(g);
  ASSERT_TRUE(back);
  EXPECT_TRUE(back->has(GlobalCommand::freeze));
  EXPECT_FALSE(back->has(GlobalCommand::clear_data));

  const SetSlaveAdd ssa{42, 0x1234, true};
  std::array<std::uint8_t, 4> s{};
  ASSERT_EQ(encode(ssa, s), 4u);
  EXPECT_EQ(hex(s, 4), "2a 12 34 01");
  EXPECT_EQ(decode_set_slave_add(s), ssa);
  EXPECT_FALSE(decode_set_slave_add(std::span<const std::uint8_t>(s).first(3)));
}

}  // namespace
}  // namespace cellctl::profibus
