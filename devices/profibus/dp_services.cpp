#include "profibus/dp_services.hpp"

#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::profibus {

namespace {
// Set_Prm octet 1 (station status) bits.
constexpr std::uint8_t kWdOn = 0x08;
constexpr std::uint8_t kFreezeReq = 0x10;
constexpr std::uint8_t kSyncReq = 0x20;
constexpr std::uint8_t kUnlockReq = 0x40;
constexpr std::uint8_t kLockReq = 0x80;
}  // namespace

std::size_t encode(const PrmStandard& p, std::span<std::uint8_t> out) noexcept {
  if (out.size() < kPrmStandardSize) return 0;
  wire::ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>((p.wd_on ? kWdOn : 0) | (p.freeze_req ? kFreezeReq : 0) |
                                 (p.sync_req ? kSyncReq : 0) | (p.unlock_req ? kUnlockReq : 0) |
                                 (p.lock_req ? kLockReq : 0)));
  w.u8(p.wd_fact_1);
  w.u8(p.wd_fact_2);
  w.u8(p.min_tsdr_bits);
  w.be(p.ident);
  w.u8(p.group);
  return w.size();
}

std::optional<PrmStandard> decode_prm_standard(std::span<const std::uint8_t> bytes) noexcept {
  wire::ByteReader r(bytes);
  const std::uint8_t status = r.u8();
  PrmStandard p;
  p.wd_fact_1 = r.u8();
  p.wd_fact_2 = r.u8();
  p.min_tsdr_bits = r.u8();
  p.ident = r.be<std::uint16_t>();
  p.group = r.u8();
  if (!r.ok()) return std::nullopt;
  p.wd_on = (status & kWdOn) != 0;
  p.freeze_req = (status & kFreezeReq) != 0;
  p.sync_req = (status & kSyncReq) != 0;
  p.unlock_req = (status & kUnlockReq) != 0;
  p.lock_req = (status & kLockReq) != 0;
  return p;
}

std::size_t encode(const GlobalControl& gc, std::span<std::uint8_t> out) noexcept {
  if (out.size() < kGlobalControlSize) return 0;
  out[0] = gc.command;
  out[1] = gc.group_select;
  return kGlobalControlSize;
}

std::optional<GlobalControl> decode_global_control(std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.size() < kGlobalControlSize) return std::nullopt;
  return GlobalControl{bytes[0], bytes[1]};
}

std::size_t encode(const SetSlaveAdd& req, std::span<std::uint8_t> out) noexcept {
  if (out.size() < kSetSlaveAddSize) return 0;
  wire::ByteWriter w(out);
  w.u8(req.new_address);
  w.be(req.ident);
  w.u8(req.no_add_chg ? 1 : 0);
  return w.size();
}

std::optional<SetSlaveAdd> decode_set_slave_add(std::span<const std::uint8_t> bytes) noexcept {
  wire::ByteReader r(bytes);
  SetSlaveAdd req;
  req.new_address = r.u8();
  req.ident = r.be<std::uint16_t>();
  req.no_add_chg = r.u8() != 0;
  if (!r.ok()) return std::nullopt;
  return req;
}

}  // namespace cellctl::profibus
