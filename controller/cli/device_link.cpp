#include "cli/device_link.hpp"

#include <fmt/format.h>

#include <cerrno>

#include "cli/publish_lock.hpp"
#include "link/link_error.hpp"
#include "link/serial_link.hpp"

namespace cellctl::cli {
namespace {

// Why the port `cellctl emulate` publishes did not open, told by whether an emulation is live (its
// publish lock): none runs — start one; one runs and the port is busy — another command talks to
// the device now.
std::string emulation_advice(const config::PortConfig& port, const std::string& name, int cause) {
  const auto emulator = PublishLock::holder(port.publish_as);
  if (!emulator)
    return fmt::format(
        " (the cell config says the {} is emulated: start `cellctl emulate` first, or give --port)", name);
  const std::string pid = emulator->empty() ? "" : fmt::format(" (pid {})", *emulator);
  if (cause == EBUSY)
    return fmt::format(
        " (`cellctl emulate`{} publishes it; another command talks to the {} now: wait for it to end)", pid,
        name);
  return fmt::format(" (`cellctl emulate`{} publishes it)", pid);
}

}  // namespace

DeviceLink::DeviceLink(const config::PortConfig& port, const std::optional<std::string>& override_port,
                       std::string name, const link::Clock& clock, bool trace) {
  const bool published = !override_port && port.emulated();
  path_ = override_port ? *override_port : published ? port.publish_as : port.port;
  try {
    serial_ = link::SerialLink::open(path_, port.line);
  } catch (const link::LinkError& e) {
    throw link::LinkError(
        fmt::format("{}: {}{}", name, e.what(), published ? emulation_advice(port, name, e.cause()) : ""),
        e.cause());
  }
  if (trace) traced_ = std::make_unique<link::TracingLink>(*serial_, clock, sink_, std::move(name));
}

DeviceLink::~DeviceLink() = default;

link::Link& DeviceLink::link() noexcept {
  return traced_ ? static_cast<link::Link&>(*traced_) : *serial_;
}

}  // namespace cellctl::cli
