#pragma once
// A serial port through termios: real RS232/USB adapters and pseudo-terminals alike. Opened
// exclusively (a second cellctl on the same port is refused, not interleaved), raw, non-blocking,
// with DTR and RTS held active because the SCU's RS232 converter is powered from them.

#include <memory>
#include <string>

#include "link/line_format.hpp"
#include "link/link.hpp"

namespace cellctl::link {

class SerialLink final : public Link {
 public:
  // Throws LinkError naming the port and what is wrong (missing, busy, no permission, bad baud).
  static std::unique_ptr<SerialLink> open(const std::string& path, LineFormat format);
  ~SerialLink() override;
  SerialLink(const SerialLink&) = delete;
  SerialLink& operator=(const SerialLink&) = delete;

  IoResult read(std::span<std::uint8_t> buffer) override;
  IoResult write(std::span<const std::uint8_t> bytes) override;
  [[nodiscard]] std::string describe() const override;
  // Closes the port and opens its path again with the same line format (exclusively, DTR/RTS held).
  // Until it succeeds, reads and writes answer IoStatus::closed.
  IoResult reopen() override;
  void arm_crash_stop(std::span<const std::uint8_t> telegram) noexcept override;

  // False on a pseudo-terminal, which has no modem lines to hold.
  [[nodiscard]] bool modem_lines_held() const noexcept { return modem_lines_held_; }

 private:
  SerialLink(int fd, std::string path, LineFormat format, bool modem_lines_held)
      : fd_(fd), path_(std::move(path)), format_(format), modem_lines_held_(modem_lines_held) {}

  int fd_;
  std::string path_;
  LineFormat format_;
  bool modem_lines_held_;
  int crash_slot_ = -1;  // crash_stop.hpp: this port's stop telegram, once armed
};

}  // namespace cellctl::link
