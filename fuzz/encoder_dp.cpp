// The encoder's DP data fed arbitrary octets: cyclic input/output, Slave_Diag (standard part and the
// encoder's extended part) and Set_Prm (standard part and User_Prm_Data), then scaling with the
// parameters the bytes carry. Properties: what decodes encodes back (to the same octets where the
// format is one-to-one, else to octets that decode the same); parameters that pass validate() scale
// every physical position into 0 … range − 1 without overflow (UBSan watches the arithmetic).

#include <array>

#include "encoder/cyclic.hpp"
#include "encoder/diagnosis.hpp"
#include "encoder/parameters.hpp"
#include "encoder/scaling.hpp"
#include "fuzz_input.hpp"
#include "profibus/dp_diag.hpp"
#include "profibus/dp_services.hpp"
#include "targets.hpp"

namespace cellctl::fuzz {
namespace {

constexpr std::array<encoder::Functionality, 5> kFunctionalities = {
    encoder::Functionality::class1, encoder::Functionality::class2, encoder::Functionality::scancon21,
    encoder::Functionality::scancon22, encoder::Functionality::scancon30};

bool same_bytes(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin());
}

// Every physical position, including both ends of the range, lands inside the measuring range.
void check_scaling(const encoder::Scaling& s, const encoder::PhysicalResolution& phys, std::uint64_t probe) {
  FUZZ_CHECK(s.range() > 0);
  for (const std::uint64_t physical : {std::uint64_t{0}, phys.total() - 1, probe % phys.total()})
    FUZZ_CHECK(s.to_units(physical) < s.range());
}

// A physical resolution the manual allows (powers of two, ≤ 2^16 steps, ≤ 2^15 revolutions).
encoder::PhysicalResolution resolution_from(std::uint8_t b) {
  encoder::PhysicalResolution phys;
  phys.steps_per_revolution = 1u << (b % 17u);
  phys.revolutions = 1u << ((b >> 4) % 16u);
  return phys;
}

}  // namespace

void encoder_cyclic(std::span<const std::uint8_t> bytes) {
  FuzzInput in(bytes);
  const std::uint8_t select = in.byte();
  const auto f = kFunctionalities[select % kFunctionalities.size()];
  const bool with_status = (select & 0x80u) != 0;
  const auto data = in.rest();

  const auto decoded = encoder::decode_input(f, with_status, data);
  if (const auto* input = std::get_if<encoder::CyclicInput>(&decoded)) {
    std::array<std::uint8_t, 8> out{};
    const std::size_t n = encoder::encode_input(f, *input, out);
    FUZZ_CHECK(same_bytes(std::span(out).first(n), data));
    FUZZ_CHECK(input->position(with_status) <=
               (with_status ? encoder::bits::position25 : encoder::bits::position31));
    (void)input->status();
    if (!with_status) FUZZ_CHECK((input->word & encoder::bits::preset) == 0);
    // The default parameters of this functionality scale the position into range.
    encoder::EncoderParameters p;
    p.functionality = f;
    const encoder::PhysicalResolution phys;
    check_scaling(encoder::Scaling(p, phys), phys, input->position(with_status));
  } else {
    FUZZ_CHECK(std::get<encoder::CyclicError>(decoded) == encoder::CyclicError::bit31_set ||
               data.size() != encoder::input_length(f));
  }
  if (const auto word = encoder::decode_output(data)) {
    std::array<std::uint8_t, 4> out{};
    FUZZ_CHECK(encoder::encode_output(*word, out) == 4);
    FUZZ_CHECK(same_bytes(out, data));
  }
}

void dp_diagnosis(std::span<const std::uint8_t> bytes) {
  // A whole Slave_Diag data unit: the six standard octets, then the extended part.
  if (const auto diag = profibus::decode_diagnosis(bytes)) {
    FUZZ_CHECK(bytes.size() >= profibus::kStandardDiagSize);
    // Nothing silently cut: the extended part is all the octets after the standard ones.
    FUZZ_CHECK(diag->extended.size() == bytes.size() - profibus::kStandardDiagSize);
    std::array<std::uint8_t, profibus::kStandardDiagSize> standard{};
    FUZZ_CHECK(profibus::encode(diag->standard, standard) == profibus::kStandardDiagSize);
    const auto again = profibus::decode_standard_diag(standard);
    FUZZ_CHECK(again && *again == diag->standard);
  } else {
    FUZZ_CHECK(bytes.size() < profibus::kStandardDiagSize ||
               bytes.size() > profibus::kStandardDiagSize + profibus::kMaxExtDiag);
  }
  // The encoder's extended diagnosis (from octet 7): both lengths, or a typed error.
  const auto ext = encoder::decode_diagnosis(bytes);
  if (const auto* d = std::get_if<encoder::EncoderDiagnosis>(&ext)) {
    FUZZ_CHECK(d->length() == bytes.size());
    std::array<std::uint8_t, encoder::kExtDiagLong> out{};
    const std::size_t n = encoder::encode_diagnosis(*d, out);
    FUZZ_CHECK(n == bytes.size());
    const auto again = encoder::decode_diagnosis(std::span(out).first(n));
    const auto* d2 = std::get_if<encoder::EncoderDiagnosis>(&again);
    FUZZ_CHECK(d2 != nullptr && *d2 == *d);
  }
}

void dp_parameters(std::span<const std::uint8_t> bytes) {
  FuzzInput in(bytes);
  const std::uint8_t select = in.byte();
  const auto f = kFunctionalities[select % kFunctionalities.size()];
  const auto phys = resolution_from(in.byte());
  std::uint64_t probe = 0;
  for (int i = 0; i < 8; ++i) probe = probe << 8 | in.byte();

  // Set_Prm's standard octets, then the User_Prm_Data, as a master sends them.
  const auto prm = in.rest();
  if (const auto standard = profibus::decode_prm_standard(prm)) {
    std::array<std::uint8_t, profibus::kPrmStandardSize> out{};
    FUZZ_CHECK(profibus::encode(*standard, out) == profibus::kPrmStandardSize);
    const auto again = profibus::decode_prm_standard(out);
    FUZZ_CHECK(again && *again == *standard);
  }
  const auto user = prm.size() > profibus::kPrmStandardSize ? prm.subspan(profibus::kPrmStandardSize) : prm;
  const auto decoded = encoder::decode_user_prm(f, user);
  if (const auto* violation = std::get_if<encoder::PrmViolation>(&decoded)) {
    FUZZ_CHECK(!violation->describe().empty());
    return;
  }
  const auto& p = std::get<encoder::EncoderParameters>(decoded);
  FUZZ_CHECK(p.functionality == f);
  std::array<std::uint8_t, 32> out{};
  const std::size_t n = encoder::encode_user_prm(p, out);
  FUZZ_CHECK(n == encoder::user_prm_length(f));
  const auto again = encoder::decode_user_prm(f, std::span(out).first(n));
  const auto* p2 = std::get_if<encoder::EncoderParameters>(&again);
  FUZZ_CHECK(p2 != nullptr && *p2 == p);
  if (const auto violation = encoder::validate(p, phys)) {
    FUZZ_CHECK(!violation->describe().empty());
    return;
  }
  check_scaling(encoder::Scaling(p, phys), phys, probe);
}

}  // namespace cellctl::fuzz
