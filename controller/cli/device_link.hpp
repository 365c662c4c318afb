#pragma once
// Opens the serial link a commissioning command talks over: the --port given on the command line,
// else the configured port, else — for a device the cell config marks "emulated" — the pseudo-terminal
// that `cellctl emulate` publishes. Wraps it in a hex trace when --trace is on. A port that does not
// open is reported with the device's name and, for a published one, whether an emulation runs.

#include <memory>
#include <optional>
#include <string>

#include "config/line_section.hpp"
#include "link/clock.hpp"
#include "link/link.hpp"
#include "link/tracing_link.hpp"

namespace cellctl::cli {

class DeviceLink {
 public:
  // Throws link::LinkError with advice when the port cannot be opened.
  DeviceLink(const config::PortConfig& port, const std::optional<std::string>& override_port,
             std::string name, const link::Clock& clock, bool trace);
  ~DeviceLink();
  [[nodiscard]] link::Link& link() noexcept;
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  std::unique_ptr<link::Link> serial_;
  link::LogTraceSink sink_;
  std::unique_ptr<link::TracingLink> traced_;
};

}  // namespace cellctl::cli
