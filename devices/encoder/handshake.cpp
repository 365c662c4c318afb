#include "encoder/handshake.hpp"

namespace cellctl::encoder {

std::string_view to_string(Handshake::Kind k) noexcept {
  switch (k) {
    case Handshake::Kind::none:
      return "none";
    case Handshake::Kind::preset:
      return "preset";
    case Handshake::Kind::direction:
      return "direction";
    case Handshake::Kind::teach_in_start:
      return "teach-in start";
    case Handshake::Kind::teach_in_end:
      return "teach-in end";
  }
  return "?";
}

bool Handshake::begin(Kind k, std::uint32_t request_word) noexcept {
  if (busy()) return false;
  kind_ = k;
  phase_ = Phase::request;
  request_word_ = request_word;
  exchanges_ = 0;
  result_ = 0;
  failure_ = {};
  return true;
}

bool Handshake::start_preset(std::uint32_t value, bool with_status) noexcept {
  if (value > (with_status ? bits::position25 : bits::position31) || busy()) return false;
  with_status_ = with_status;
  return begin(Kind::preset, bits::preset | value);
}

bool Handshake::start_direction(CodeSequence wanted) noexcept {
  if (busy()) return false;
  wanted_ = wanted;
  return begin(Kind::direction, bits::code_sequence | (wanted == CodeSequence::ccw ? 1u : 0u));
}

bool Handshake::start_teach_in() noexcept {
  return begin(Kind::teach_in_start, bits::teach_in_start);
}

bool Handshake::end_teach_in(std::uint32_t distance) noexcept {
  if (distance == 0 || distance > bits::position25) return false;
  return begin(Kind::teach_in_end, bits::teach_in_end | distance);
}

std::uint32_t Handshake::output() const noexcept {
  return phase_ == Phase::request ? request_word_ : 0u;
}

void Handshake::advance(bool acknowledged, std::string_view what) noexcept {
  if (acknowledged) {
    phase_ = phase_ == Phase::request ? Phase::release : Phase::done;
    exchanges_ = 0;
    return;
  }
  if (++exchanges_ >= kMaxExchanges) {
    phase_ = Phase::failed;
    failure_ = what;
  }
}

void Handshake::on_input(const CyclicInput& in) noexcept {
  if (!busy()) return;
  const std::uint32_t w = in.word;
  const bool requesting = phase_ == Phase::request;
  const bool ccw = (w & bits::code_sequence) != 0;
  switch (kind_) {
    case Kind::preset:
      if (!with_status_) {  // no acknowledge bit: one exchange per phase (4.3.2)
        result_ = in.position(false);
        advance(true, {});
        return;
      }
      result_ = in.position(true);
      if (requesting)
        advance((w & bits::preset) != 0, "preset not acknowledged (bit 31 never set by the encoder)");
      else
        advance((w & bits::preset) == 0, "preset acknowledge not released (bit 31 stays set)");
      return;
    case Kind::direction: {
      const bool wanted_ccw = wanted_ == CodeSequence::ccw;
      if (requesting)
        advance(ccw == wanted_ccw && in.position(true) == (wanted_ccw ? 1u : 0u),
                "direction change not acknowledged (bit 28/bit 0 never showed the new sequence)");
      else {
        result_ = in.position(true);
        advance(ccw == wanted_ccw, "direction change lost (bit 28 not the requested sequence)");
      }
      return;
    }
    case Kind::teach_in_start:
      if (requesting)
        advance((w & bits::teach_in_start) != 0 && (w & bits::teach_in_end) == 0,
                "Teach-In start not acknowledged (bit 30 never set; commissioning mode?)");
      else {
        result_ = in.position(true);
        advance((w & bits::teach_in_start) != 0, "Teach-In not running after start (bit 30 clear)");
      }
      return;
    case Kind::teach_in_end:
      if (requesting) {
        const bool ack = (w & bits::teach_in_end) != 0 && (w & bits::teach_in_start) != 0;
        if (ack) result_ = in.position(true);
        advance(ack,
                "Teach-In end not acknowledged (bits 29/30 never set; Teach-In started? distance moved?)");
      } else {
        advance((w & (bits::teach_in_end | bits::teach_in_start)) == 0,
                "Teach-In end not released (bits 29/30 stay set)");
      }
      return;
    case Kind::none:
      return;
  }
}

}  // namespace cellctl::encoder
