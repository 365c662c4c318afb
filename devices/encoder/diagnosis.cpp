#include "encoder/diagnosis.hpp"

#include "encoder/functionality.hpp"
#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::encoder {
namespace {

std::uint8_t status_byte(const OperatingStatus& s) noexcept {
  return static_cast<std::uint8_t>((s.ccw ? 1u : 0u) | (s.class2 ? 2u : 0u) |
                                   (s.commissioning_diagnostics ? 4u : 0u) | (s.scaling ? 8u : 0u));
}

}  // namespace

std::string_view to_string(DiagError e) noexcept {
  switch (e) {
    case DiagError::bad_length:
      return "extended diagnosis must be 10 or 51 octets";
    case DiagError::header_mismatch:
      return "extended diagnosis header does not match its length";
    case DiagError::unassigned_bits_set:
      return "unassigned alarm/status bits set";
  }
  return "?";
}

std::size_t EncoderDiagnosis::length() const noexcept {
  return detail ? kExtDiagLong : kExtDiagShort;
}

std::variant<EncoderDiagnosis, DiagError> decode_diagnosis(std::span<const std::uint8_t> ext) noexcept {
  if (ext.size() != kExtDiagShort && ext.size() != kExtDiagLong) return DiagError::bad_length;
  wire::ByteReader r(ext);
  if (r.u8() != ext.size()) return DiagError::header_mismatch;
  EncoderDiagnosis d;
  d.alarms = r.u8();
  const std::uint8_t status = r.u8();
  if ((d.alarms & 0xE0u) != 0 || (status & 0xF0u) != 0) return DiagError::unassigned_bits_set;
  d.status = OperatingStatus{(status & 1u) != 0, (status & 2u) != 0, (status & 4u) != 0, (status & 8u) != 0};
  d.encoder_type = r.u8();
  d.singleturn_resolution = r.be<std::uint32_t>();
  d.revolutions = r.be<std::uint16_t>();
  if (ext.size() == kExtDiagLong) {
    DiagnosisDetail x;
    x.additional_alarms = r.u8();
    x.supported_alarms = r.be<std::uint16_t>();
    x.warnings = r.be<std::uint16_t>();
    x.supported_warnings = r.be<std::uint16_t>();
    x.profile_version = Version{r.u8(), r.u8()};
    x.software_version = Version{r.u8(), r.u8()};
    x.operating_time_tenth_h = r.be<std::uint32_t>();
    x.offset = r.be<std::int32_t>();
    x.manufacturer_offset = r.be<std::int32_t>();
    x.units_per_revolution = r.be<std::uint32_t>();
    x.total_range = r.be<std::uint32_t>();
    for (char& c : x.serial) c = static_cast<char>(r.u8());
    d.detail = x;
  }
  return d;
}

std::size_t encode_diagnosis(const EncoderDiagnosis& d, std::span<std::uint8_t> out) noexcept {
  const std::size_t n = d.length();
  if (out.size() < n) return 0;
  wire::ByteWriter w(out.first(n));
  w.u8(static_cast<std::uint8_t>(n));
  w.u8(d.alarms);
  w.u8(status_byte(d.status));
  w.u8(d.encoder_type);
  w.be(d.singleturn_resolution);
  w.be(d.revolutions);
  if (const auto& x = d.detail) {
    w.u8(x->additional_alarms);
    w.be(x->supported_alarms);
    w.be(x->warnings);
    w.be(x->supported_warnings);
    w.u8(x->profile_version.major);
    w.u8(x->profile_version.minor);
    w.u8(x->software_version.major);
    w.u8(x->software_version.minor);
    w.be(x->operating_time_tenth_h);
    w.be(x->offset);
    w.be(x->manufacturer_offset);
    w.be(x->units_per_revolution);
    w.be(x->total_range);
    for (char c : x->serial) w.u8(static_cast<std::uint8_t>(c));
  }
  return w.ok() ? w.size() : 0;
}

}  // namespace cellctl::encoder
