#include "encoder/cyclic.hpp"

#include <chrono>
#include <cmath>

#include "wire/byte_reader.hpp"
#include "wire/byte_writer.hpp"

namespace cellctl::encoder {

StatusBits CyclicInput::status() const noexcept {
  return StatusBits{(word & bits::ready) != 0,        (word & bits::mode) == 0,
                    (word & bits::limit_switch) != 0, (word & bits::code_sequence) != 0,
                    (word & bits::teach_in_end) != 0, (word & bits::teach_in_start) != 0,
                    (word & bits::preset) != 0};
}

std::string_view to_string(CyclicError e) noexcept {
  switch (e) {
    case CyclicError::bad_length:
      return "input length does not match the functionality";
    case CyclicError::bit31_set:
      return "bit 31 set in a position without status bits";
  }
  return "?";
}

std::variant<CyclicInput, CyclicError> decode_input(Functionality f, bool with_status,
                                                    std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.size() != input_length(f)) return CyclicError::bad_length;
  wire::ByteReader r(bytes);
  CyclicInput in;
  in.word = r.be<std::uint32_t>();
  if (!with_status && (in.word & bits::preset) != 0) return CyclicError::bit31_set;
  if (f == Functionality::scancon22 || f == Functionality::scancon30) in.velocity = r.be<std::int16_t>();
  if (f == Functionality::scancon30) in.acceleration = r.be<std::int16_t>();
  return in;
}

std::size_t encode_input(Functionality f, const CyclicInput& in, std::span<std::uint8_t> out) noexcept {
  const std::size_t n = input_length(f);
  if (out.size() < n) return 0;
  wire::ByteWriter w(out.first(n));
  w.be(in.word);
  if (f == Functionality::scancon22 || f == Functionality::scancon30) w.be(in.velocity);
  if (f == Functionality::scancon30) w.be(in.acceleration);
  return w.size();
}

std::optional<std::uint32_t> decode_output(std::span<const std::uint8_t> bytes) noexcept {
  if (bytes.size() != 4) return std::nullopt;
  wire::ByteReader r(bytes);
  return r.be<std::uint32_t>();
}

std::size_t encode_output(std::uint32_t word, std::span<std::uint8_t> out) noexcept {
  if (out.size() < 4) return 0;
  wire::ByteWriter w(out.first(4));
  w.be(word);
  return 4;
}

std::int16_t saturate16(double v) noexcept {
  if (std::isnan(v)) return 0;
  if (v >= INT16_MAX) return INT16_MAX;
  if (v <= INT16_MIN) return INT16_MIN;
  return static_cast<std::int16_t>(std::lround(v));
}

link::Duration sample_period(TimeBase tb) noexcept {
  using namespace std::chrono_literals;
  switch (tb) {
    case TimeBase::steps_per_100ms:
      return 100ms;
    case TimeBase::steps_per_10ms:
      return 10ms;
    case TimeBase::steps_per_s:
    case TimeBase::rpm:
      return 1s;
  }
  return 1s;
}

double units_per_second(double value, TimeBase tb, double units_per_revolution) noexcept {
  if (tb == TimeBase::rpm) return value * units_per_revolution / 60.0;
  return value / link::to_seconds(sample_period(tb));
}

double in_time_base(double units_per_s, TimeBase tb, double units_per_revolution) noexcept {
  if (tb == TimeBase::rpm) return units_per_revolution > 0 ? units_per_s * 60.0 / units_per_revolution : 0.0;
  return units_per_s * link::to_seconds(sample_period(tb));
}

}  // namespace cellctl::encoder
