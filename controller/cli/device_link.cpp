#include "cli/device_link.hpp"

#include <fmt/format.h>

#include "link/link_error.hpp"
#include "link/serial_link.hpp"

namespace cellctl::cli {

DeviceLink::DeviceLink(const config::PortConfig& port, const std::optional<std::string>& override_port,
                       std::string name, const link::Clock& clock, bool trace) {
  path_ = override_port ? *override_port : port.emulated() ? port.publish_as : port.port;
  try {
    serial_ = link::SerialLink::open(path_, port.line);
  } catch (const link::LinkError& e) {
    if (!override_port && port.emulated())
      throw link::LinkError(
          fmt::format("{} (the cell config says the {} is emulated: start `cellctl emulate` first, "
                      "or give --port)",
                      e.what(), name));
    throw;
  }
  if (trace) traced_ = std::make_unique<link::TracingLink>(*serial_, clock, sink_, std::move(name));
}

DeviceLink::~DeviceLink() = default;

link::Link& DeviceLink::link() noexcept {
  return traced_ ? static_cast<link::Link&>(*traced_) : *serial_;
}

}  // namespace cellctl::cli
