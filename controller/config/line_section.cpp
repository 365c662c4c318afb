#include "config/line_section.hpp"

namespace cellctl::config {

PortConfig parse_port(const YamlNode& section, std::string_view device, const link::LineFormat& defaults) {
  PortConfig out;
  out.line = defaults;
  out.port = section.string_or("port", "emulated");
  if (out.port.empty()) section.at("port").fail("must name a serial port or 'emulated'");
  // Paths relative to the config file, as every path in a config (a pseudo-terminal published beside it).
  if (!out.emulated()) out.port = section.at("port").as_path().string();
  out.publish_as = section.path_or("publish_as", "/tmp/cellctl-" + std::string(device)).string();
  if (const auto baud = section.maybe("baud")) {
    out.line.baud = static_cast<std::uint32_t>(baud->as_integer_in(1200, 12'000'000));
  }
  out.line.data_bits = section.int_in_or<std::uint8_t>("data_bits", 5, 8, defaults.data_bits);
  out.line.stop_bits = section.int_in_or<std::uint8_t>("stop_bits", 1, 2, defaults.stop_bits);
  if (const auto parity = section.maybe("parity")) {
    const auto p = parity->as_choice({"none", "even", "odd"});
    out.line.parity = p == "none" ? link::Parity::none : p == "even" ? link::Parity::even : link::Parity::odd;
  }
  return out;
}

}  // namespace cellctl::config
