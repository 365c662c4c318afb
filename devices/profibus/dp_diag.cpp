#include "profibus/dp_diag.hpp"

#include <fmt/format.h>

#include <utility>

#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::profibus {

namespace {
constexpr std::uint8_t bit(bool on, unsigned n) noexcept {
  return static_cast<std::uint8_t>(on ? (1u << n) : 0u);
}
constexpr bool has(std::uint8_t octet, unsigned n) noexcept {
  return ((static_cast<unsigned>(octet) >> n) & 1u) != 0;
}
constexpr std::uint8_t kStatus2Fixed = 0x04;  // octet 2 bit 2 is always 1 in a slave's reply
}  // namespace

std::size_t encode(const StandardDiag& d, std::span<std::uint8_t> out) noexcept {
  if (out.size() < kStandardDiagSize) return 0;
  wire::ByteWriter w(out);
  w.u8(static_cast<std::uint8_t>(bit(d.station_non_existent, 0) | bit(d.station_not_ready, 1) |
                                 bit(d.cfg_fault, 2) | bit(d.ext_diag, 3) | bit(d.not_supported, 4) |
                                 bit(d.invalid_slave_response, 5) | bit(d.prm_fault, 6) |
                                 bit(d.master_lock, 7)));
  w.u8(static_cast<std::uint8_t>(bit(d.prm_req, 0) | bit(d.stat_diag, 1) | kStatus2Fixed | bit(d.wd_on, 3) |
                                 bit(d.freeze_mode, 4) | bit(d.sync_mode, 5) | bit(d.deactivated, 7)));
  w.u8(bit(d.ext_diag_overflow, 7));
  w.u8(d.master_address);
  w.be(d.ident);
  return w.size();
}

std::optional<StandardDiag> decode_standard_diag(std::span<const std::uint8_t> bytes) noexcept {
  wire::ByteReader r(bytes);
  const std::uint8_t s1 = r.u8();
  const std::uint8_t s2 = r.u8();
  const std::uint8_t s3 = r.u8();
  StandardDiag d;
  d.master_address = r.u8();
  d.ident = r.be<std::uint16_t>();
  if (!r.ok()) return std::nullopt;
  d.station_non_existent = has(s1, 0);
  d.station_not_ready = has(s1, 1);
  d.cfg_fault = has(s1, 2);
  d.ext_diag = has(s1, 3);
  d.not_supported = has(s1, 4);
  d.invalid_slave_response = has(s1, 5);
  d.prm_fault = has(s1, 6);
  d.master_lock = has(s1, 7);
  d.prm_req = has(s2, 0);
  d.stat_diag = has(s2, 1);
  d.wd_on = has(s2, 3);
  d.freeze_mode = has(s2, 4);
  d.sync_mode = has(s2, 5);
  d.deactivated = has(s2, 7);
  d.ext_diag_overflow = has(s3, 7);
  return d;
}

DiagText describe(const StandardDiag& d) noexcept {
  DiagText t;
  const auto add = [&t](std::string_view s) {
    if (t.size + s.size() + 1 > t.chars.size()) return;
    if (t.size > 0) t.chars[t.size++] = ' ';
    std::copy(s.begin(), s.end(), t.chars.begin() + static_cast<std::ptrdiff_t>(t.size));
    t.size += s.size();
  };
  const std::pair<bool, std::string_view> flags[] = {
      {d.station_non_existent, "Station_Non_Existent"},
      {d.station_not_ready, "Station_Not_Ready"},
      {d.cfg_fault, "Cfg_Fault"},
      {d.ext_diag, "Ext_Diag"},
      {d.not_supported, "Not_Supported"},
      {d.invalid_slave_response, "Invalid_Slave_Response"},
      {d.prm_fault, "Prm_Fault"},
      {d.master_lock, "Master_Lock"},
      {d.prm_req, "Prm_Req"},
      {d.stat_diag, "Stat_Diag"},
      {d.wd_on, "WD_On"},
      {d.freeze_mode, "Freeze_Mode"},
      {d.sync_mode, "Sync_Mode"},
      {d.deactivated, "Deactivated"},
      {d.ext_diag_overflow, "Ext_Diag_Overflow"},
  };
  for (const auto& [on, name] : flags)
    if (on) add(name);
  if (t.size == 0) add("no flags");
  std::array<char, 48> tail{};
  const auto r = d.master_address == kNoMaster
                     ? fmt::format_to_n(tail.data(), tail.size(), ", master none, ident 0x{:04X}", d.ident)
                     : fmt::format_to_n(tail.data(), tail.size(), ", master {}, ident 0x{:04X}",
                                        d.master_address, d.ident);
  const std::size_t n = std::min(r.size, tail.size());
  if (t.size + n <= t.chars.size()) {
    std::copy_n(tail.begin(), n, t.chars.begin() + static_cast<std::ptrdiff_t>(t.size));
    t.size += n;
  }
  return t;
}

std::optional<DpDiagnosis> decode_diagnosis(std::span<const std::uint8_t> bytes) noexcept {
  const auto standard = decode_standard_diag(bytes);
  if (!standard) return std::nullopt;
  DpDiagnosis d;
  d.standard = *standard;
  // More extended octets than a DP data unit carries is not a diagnosis a slave can send: refuse
  // it whole rather than keep a cut-off part that would read as a complete one.
  if (!d.extended.assign(bytes.subspan(kStandardDiagSize))) return std::nullopt;
  return d;
}

}  // namespace cellctl::profibus
