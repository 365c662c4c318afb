#pragma once
// The fuzz targets: each takes arbitrary bytes, drives one decoder or loader with them and aborts
// (FUZZ_CHECK, or a sanitizer) when a property breaks. Built into libFuzzer executables by the
// `fuzz` preset (clang) and replayed over fuzz/corpus and fuzz/findings by tests/fuzz under g++.

#include <cstdint>
#include <span>
#include <string_view>

namespace cellctl::fuzz {

using Target = void (*)(std::span<const std::uint8_t>);

void scu_request_stream(std::span<const std::uint8_t> bytes);
void scu_reply_stream(std::span<const std::uint8_t> bytes);
void spindle_frames(std::span<const std::uint8_t> bytes);
void fdl_frames(std::span<const std::uint8_t> bytes);
void encoder_cyclic(std::span<const std::uint8_t> bytes);
void dp_diagnosis(std::span<const std::uint8_t> bytes);
void dp_parameters(std::span<const std::uint8_t> bytes);
void yaml_config(std::span<const std::uint8_t> bytes);
void yaml_recipe(std::span<const std::uint8_t> bytes);
void command_payload(std::span<const std::uint8_t> bytes);

struct NamedTarget {
  std::string_view name;  // also the folder of its corpus and findings
  Target run;
};

inline constexpr NamedTarget kTargets[] = {
    {"scu_request_stream", scu_request_stream},
    {"scu_reply_stream", scu_reply_stream},
    {"spindle_frames", spindle_frames},
    {"fdl_frames", fdl_frames},
    {"encoder_cyclic", encoder_cyclic},
    {"dp_diagnosis", dp_diagnosis},
    {"dp_parameters", dp_parameters},
    {"yaml_config", yaml_config},
    {"yaml_recipe", yaml_recipe},
    {"command_payload", command_payload},
};

}  // namespace cellctl::fuzz
