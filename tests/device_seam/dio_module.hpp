#pragma once
// A small digital I/O module, made up for the device seam's test: a fourth kind of device that the
// cell knows nothing of, added through the registry alone (device_seam/device_registry.hpp). It is a
// device as far as the seam can tell: a line protocol of its own, a session over a link, an emulator on
// the other end, its part of the intents (the coolant valve on output 0 follows the spindle) and its own
// safe-stop (every output off, confirmed by reading it back).
//
// Its protocol, ASCII lines: "R\n" reads, "W hh\n" writes the outputs; the module answers every line
// with "O hh\n", the outputs in force (two hex digits).

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "config/line_section.hpp"
#include "device_seam/cell_device.hpp"
#include "device_seam/device_registry.hpp"
#include "emulation/emulated_device.hpp"
#include "link/device_session.hpp"
#include "link/link.hpp"

namespace cellctl::testing::dio {

using namespace std::chrono_literals;

inline constexpr link::Duration kPollPeriod = 20ms;
inline constexpr link::Duration kReplyTimeout = 50ms;
inline constexpr link::Duration kFaultAfter = 200ms;

// The module's end of the line.
class Emulator {
 public:
  explicit Emulator(link::Link& link) : link_(link) {}
  void poll() {
    std::array<std::uint8_t, 64> buf{};
    const auto r = link_.read(buf);
    for (std::size_t i = 0; i < r.count; ++i) {
      const char c = static_cast<char>(buf[i]);
      if (c != '\n') {
        line_ += c;
        continue;
      }
      if (line_.size() == 4 && line_[0] == 'W')
        outputs_ = static_cast<std::uint8_t>(std::stoul(line_.substr(2), nullptr, 16));
      line_.clear();
      if (!silent_) {
        const auto reply = fmt::format("O {:02x}\n", outputs_);
        (void)link_.write(std::span(reinterpret_cast<const std::uint8_t*>(reply.data()), reply.size()));
      }
    }
  }
  [[nodiscard]] std::uint8_t outputs() const noexcept { return outputs_; }
  void set_silent(bool silent) noexcept { silent_ = silent; }

 private:
  link::Link& link_;
  std::string line_;
  std::uint8_t outputs_ = 0;
  bool silent_ = false;
};

// The master's end: polls the outputs, writes a change, faults after kFaultAfter without a good reply.
class Session final : public link::DeviceSession {
 public:
  explicit Session(link::Link& link) : link_(link) {}
  void activate(link::TimePoint now) override { enter(link::Lifecycle::activating, now); }
  void deactivate(link::TimePoint) override {
    wanted_ = 0;
    if (lifecycle() == link::Lifecycle::active) enter(link::Lifecycle::deactivating);
  }
  void receive(link::TimePoint now) override {
    std::array<std::uint8_t, 64> buf{};
    const auto r = link_.read(buf);
    for (std::size_t i = 0; i < r.count; ++i) take(static_cast<char>(buf[i]), now);
    if (sent_at_ && now - *sent_at_ > kReplyTimeout) {
      ++health_.timeouts;
      sent_at_.reset();
    }
    if (!quiet() && silent_for(now) > kFaultAfter)
      enter_fault("dio silent for {} ms", (silent_for(now) / 1ms));
  }
  void transmit(link::TimePoint now) override {
    if (quiet() || sent_at_) return;
    if (wanted_ != outputs_) return send(fmt::format("W {:02x}\n", wanted_), now);
    if (now - polled_at_ >= kPollPeriod) send("R\n", now);
  }
  [[nodiscard]] const link::LinkHealth& health() const noexcept override { return health_; }
  [[nodiscard]] bool awaiting_reply() const noexcept override { return sent_at_.has_value(); }

  void set_outputs(std::uint8_t outputs) noexcept { wanted_ = outputs; }
  [[nodiscard]] std::optional<std::uint8_t> outputs() const noexcept { return outputs_; }

 private:
  void send(const std::string& line, link::TimePoint now) {
    (void)link_.write(std::span(reinterpret_cast<const std::uint8_t*>(line.data()), line.size()));
    sent_at_ = polled_at_ = now;
  }
  void take(char c, link::TimePoint now) {
    if (c != '\n') {
      line_ += c;
      return;
    }
    if (line_.size() == 4 && line_[0] == 'O' && sent_at_) {
      outputs_ = static_cast<std::uint8_t>(std::stoul(line_.substr(2), nullptr, 16));
      health_.record_reply(*sent_at_, now);
      sent_at_.reset();
      if (lifecycle() == link::Lifecycle::activating) enter(link::Lifecycle::active);
      if (lifecycle() == link::Lifecycle::deactivating && outputs_ == 0) enter(link::Lifecycle::inactive);
    } else {
      ++health_.bad_frames;
    }
    line_.clear();
  }

  link::Link& link_;
  link::LinkHealth health_;
  std::string line_;
  std::optional<link::TimePoint> sent_at_;
  link::TimePoint polled_at_{};
  std::uint8_t wanted_ = 0;
  std::optional<std::uint8_t> outputs_;
};

// The module above its session: output 0 is the coolant valve, open while the spindle is asked to run
// and no halt is in force. Its safe-stop: every output off, observed once the module reads back 0;
// without an answer within confirm_within it is unknown (a valve may still be open).
class Device final : public device_seam::CellDevice {
 public:
  Device(std::size_t slot, link::Link& link, Reopen reopen)
      : CellDevice(slot, "dio", "I/O module", std::move(reopen)), session_(link) {}

  [[nodiscard]] link::DeviceSession& session() noexcept override { return session_; }
  [[nodiscard]] const link::DeviceSession& session() const noexcept override { return session_; }
  [[nodiscard]] Session& dio() noexcept { return session_; }

  void read(link::TimePoint, cell::CellState&) override {}  // no slot of its own beyond its link
  void apply(const cell::Intents& in) override {
    session_.set_outputs(in.spindle.run && in.halt == cell::Halt::none ? 0x01 : 0x00);
  }
  void begin_stop(link::TimePoint now) override { session_.deactivate(now); }
  void step_stop(link::TimePoint now, const device_seam::StopContext& ctx) override {
    if (resolved()) return;
    if (session_.lifecycle() == link::Lifecycle::inactive) return resolve(device_seam::Safe::observed, now);
    if (session_.lifecycle() == link::Lifecycle::fault) recover(now);
    if (now >= ctx.begun_at.value_or(lost_at().value_or(now)) + ctx.confirm_within)
      resolve(device_seam::Safe::unknown, now);
  }
  [[nodiscard]] std::string evidence(const device_seam::StopContext& ctx) const override {
    return loss_evidence("I/O module", ctx) +
           (resolved() == device_seam::Safe::observed
                ? fmt::format("every output off, read back at {:.3f} s", ctx.t_of(resolved_at()))
                : std::string("outputs never read back off: the coolant valve may still be open"));
  }

 private:
  Session session_;
};

inline std::unique_ptr<device_seam::CellDevice> make(std::size_t slot, const config::CellConfig&,
                                                     link::Link& link,
                                                     device_seam::CellDevice::Reopen reopen) {
  return std::make_unique<Device>(slot, link, std::move(reopen));
}

// The module's end of the line in the emulated cell; its own error: it stops answering.
class Emulated final : public emulation::EmulatorOf<Emulator> {
 public:
  explicit Emulated(link::Link& link) : emulator_(link) {}
  Emulator& emulator() noexcept override { return emulator_; }
  void poll(link::TimePoint) override { emulator_.poll(); }
  void set_own_error(bool on) override { emulator_.set_silent(on); }

 private:
  Emulator emulator_;
};

inline std::unique_ptr<emulation::EmulatedDevice> make_emulator(const emulation::EmulatorContext& context) {
  return std::make_unique<Emulated>(context.link);
}

// Its section of the cell config, `dio:`, holds its port and nothing else (38400 8N1 unless it says).
inline std::optional<config::PortConfig> port(const config::CellConfig& cell) {
  const auto section = cell.document ? cell.document->maybe("dio") : std::nullopt;
  if (!section) return std::nullopt;
  section->only_keys({}, config::kPortKeys);
  return config::parse_port(*section, "dio", link::line_8n1(38400));
}

// Its one registration.
inline constexpr device_seam::DeviceKind kKind{"dio", "the module stops answering (its watchdog tripped)",
                                               &port, &make, &make_emulator};

// The registry's kinds and the module's, in slot order.
inline std::vector<device_seam::DeviceKind> kinds_with_dio() {
  std::vector<device_seam::DeviceKind> kinds(device_seam::cell_device_kinds().begin(),
                                             device_seam::cell_device_kinds().end());
  kinds.push_back(kKind);
  return kinds;
}

inline constexpr const char* kCellFile = CELLCTL_SOURCE_DIR "/config/cell.yaml";
inline const std::string kDioSection = "dio:\n  port: emulated\n  baud: 38400\n";

// The demo cell with `dio_section` after it (read as if it were in config/cell.yaml).
inline config::CellConfig cell_with(const std::string& dio_section,
                                    std::span<const device_seam::DeviceKind> kinds) {
  std::ifstream in(kCellFile);
  std::stringstream text;
  text << in.rdbuf() << dio_section;
  return device_seam::parse_cell_config(config::YamlNode::load_string(text.str(), kCellFile), kCellFile,
                                        kinds);
}

}  // namespace cellctl::testing::dio
