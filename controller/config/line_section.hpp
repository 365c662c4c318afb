#pragma once
// The "where is this device" part every device section shares: a port (a device path, or
// "emulated" for the built-in emulator) and the serial line format.

#include <array>
#include <string>
#include <string_view>

#include "config/yaml_node.hpp"
#include "link/line_format.hpp"

namespace cellctl::config {

struct PortConfig {
  std::string port = "emulated";  // "emulated" or a path such as /dev/ttyUSB0
  link::LineFormat line;
  // Where `cellctl emulate` publishes the emulator's pseudo-terminal (a symlink), and so where the
  // commissioning commands look for an emulated device.
  std::string publish_as;
  [[nodiscard]] bool emulated() const noexcept { return port == "emulated"; }
};

// Reads port, publish_as, baud and the framing (data_bits/parity/stop_bits), defaulting to
// `defaults` and to /tmp/cellctl-<device> for publish_as. Callers list these keys in only_keys().
[[nodiscard]] PortConfig parse_port(const YamlNode& section, std::string_view device,
                                    const link::LineFormat& defaults);
inline constexpr std::array<std::string_view, 6> kPortKeys = {"port",      "publish_as", "baud",
                                                              "data_bits", "parity",     "stop_bits"};

}  // namespace cellctl::config
