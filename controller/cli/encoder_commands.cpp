#include "cli/encoder_commands.hpp"

#include <fmt/format.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <memory>
#include <optional>
#include <string>

#include "cli/commissioning.hpp"
#include "cli/exit_codes.hpp"
#include "config/cell_config.hpp"
#include "encoder/session.hpp"

namespace cellctl::cli {
namespace {

using namespace std::chrono_literals;

enum class Action { status, diag, preset, direction, set_address, teach_in };

struct EncoderOptions : DeviceOptions {
  EncoderOptions() { timeout_s = 10.0; }
  std::uint32_t value = 0;  // preset value, new address or Teach-In distance
  std::string direction = "cw";
};

std::string bits_text(std::uint16_t bits,
                      std::initializer_list<std::pair<std::uint16_t, const char*>> names) {
  std::string out;
  for (const auto& [mask, name] : names)
    if ((bits & mask) != 0) out += (out.empty() ? "" : ", ") + std::string(name);
  return out.empty() ? "none" : out;
}

void print_status(const encoder::Session& session) {
  const auto& s = session.snapshot();
  fmt::print("bus            {} ({}), {} exchanges, last input {:.1f} ms ago\n",
             link::to_string(session.lifecycle()), profibus::to_string(s.dp_state), s.exchanges,
             link::to_seconds(s.input_age) * 1e3);
  fmt::print("position       {} counts = {:.3f} mm\n", s.position_counts, s.position_mm);
  const auto f = session.config().parameters.functionality;
  if (f == encoder::Functionality::scancon22 || f == encoder::Functionality::scancon30)
    fmt::print("velocity       {:.3f} mm/s (raw {}{})\n", s.velocity_mm_s, s.velocity_raw,
               s.velocity_saturated ? ", SATURATED" : "");
  if (f == encoder::Functionality::scancon30)
    fmt::print("acceleration   {:.3f} mm/s² (raw {}{})\n", s.acceleration_mm_s2, s.acceleration_raw,
               s.acceleration_saturated ? ", SATURATED" : "");
  if (s.has_status_bits)
    fmt::print("status         {}, {}, {}, counting {}{}\n", s.status.ready ? "ready" : "NOT READY",
               s.status.commissioning ? "commissioning mode" : "normal mode",
               s.status.limit_switch ? "OUTSIDE LIMITS" : "within limits",
               s.status.ccw ? "up counterclockwise" : "up clockwise",
               s.status.teach_in_start ? ", Teach-In running" : "");
}

void print_diag(const encoder::Snapshot& s) {
  if (s.diagnosis_reads == 0) {
    fmt::print("diagnosis      not read yet\n");
    return;
  }
  fmt::print("diagnosis      {} read; standard part: {}\n", s.diagnosis_reads,
             profibus::describe(s.standard_diag).view());
  const bool last_decoded = s.extended_diag_octets > 0 && s.diagnosis_error.empty();
  if (s.extended_diag_octets == 0)
    fmt::print(
        "extended       none: the last diagnosis had only the 6 standard octets (the SCH88BEX sends 10 "
        "or 51 more)\n");
  else if (!last_decoded)
    fmt::print("extended       {} octets that are not the encoder profile's: {}\n", s.extended_diag_octets,
               s.diagnosis_error);
  if (!s.diagnosis) return;
  if (!last_decoded) fmt::print("earlier        the last extended diagnosis that decoded:\n");
  const auto& d = *s.diagnosis;
  using namespace encoder;
  fmt::print("alarms         {}\n", bits_text(d.alarms, {{alarm::position_error, "position error"},
                                                         {alarm::supply_voltage, "supply voltage"},
                                                         {alarm::current_too_high, "current too high"},
                                                         {alarm::memory_error, "memory error"}}));
  fmt::print("operating      counting up {}, class 2 {}, scaling {}\n",
             d.status.ccw ? "counterclockwise" : "clockwise", d.status.class2 ? "yes" : "no",
             d.status.scaling ? "on" : "off");
  fmt::print("encoder        {}, {} steps/revolution × {} revolutions\n",
             d.multiturn() ? "multiturn" : "singleturn", d.singleturn_resolution, d.revolutions);
  if (!d.detail) return;
  const auto& x = *d.detail;
  const std::initializer_list<std::pair<std::uint16_t, const char*>> warnings = {
      {warning::frequency_exceeded, "frequency exceeded"},
      {warning::temperature_exceeded, "temperature above 65 °C"},
      {warning::light_control_reserve, "LED light reserve low"},
      {warning::cpu_watchdog, "CPU watchdog"},
      {warning::operating_time_limit, "operating time above 87600 h"},
      {warning::battery_charge, "battery low"},
      {warning::reference_point, "reference point"}};
  fmt::print("warnings       {} (supported: {})\n", bits_text(x.warnings, warnings),
             bits_text(x.supported_warnings, warnings));
  fmt::print("versions       profile {}.{}, software {}.{}\n", x.profile_version.major,
             x.profile_version.minor, x.software_version.major, x.software_version.minor);
  fmt::print("operating time {:.1f} h\n", x.operating_time_tenth_h / 10.0);
  fmt::print("offset         {} (manufacturer {})\n", x.offset, x.manufacturer_offset);
  fmt::print("scaling        {} units/revolution, {} units total\n", x.units_per_revolution, x.total_range);
  fmt::print("serial         {}\n", std::string(x.serial.begin(), x.serial.end()));
}

bool enter_pressed() {
  pollfd p{STDIN_FILENO, POLLIN, 0};
  if (::poll(&p, 1, 0) <= 0) return false;
  char buf[64];
  return ::read(STDIN_FILENO, buf, sizeof buf) >= 0;
}

class EncoderCommissioning {
 public:
  EncoderCommissioning(const GlobalOptions& global, const EncoderOptions& options,
                       const config::EncoderSection& section, Action action)
      : options_(options),
        c_(global, options, section.port, "encoder", with_station(section.session, action)) {}

  int run(Action action) {
    // A preset beyond this encoder's scaling is a bad argument (manual 4.3.2): refused before the bus.
    if (const auto range = session_.scaling().range(); action == Action::preset && options_.value >= range) {
      spdlog::error("preset {}: must be 0 … {} (the total measuring range − 1)", options_.value, range - 1);
      return kExitUsage;
    }
    c_.activate();
    if (action == Action::set_address) return set_address();
    if (!drive([&] { return snapshot().data_exchange && snapshot().exchanges > 2; }))
      return failed_to("exchange data");
    switch (action) {
      case Action::preset:
        if (!session_.preset(options_.value)) return refuse("preset");
        if (!finish_command()) return failed_to("acknowledge the preset");
        break;
      case Action::direction:
        if (!session_.set_direction(options_.direction == "ccw" ? encoder::CodeSequence::ccw
                                                                : encoder::CodeSequence::cw))
          return refuse("change direction (needs status bits and commissioning: true)");
        if (!finish_command()) return failed_to("acknowledge the direction change");
        break;
      case Action::teach_in:
        return teach_in();
      default:
        break;
    }
    (void)c_.drive_for(20ms);
    print_status(session_);
    if (action == Action::diag) print_diag(snapshot());
    return kExitOk;
  }

 private:
  // Set_Slave_Add is only possible for an encoder whose switches are at 126 (manual 3.4).
  static encoder::SessionConfig with_station(encoder::SessionConfig c, Action action) {
    if (action == Action::set_address) c.station_address = 126;
    return c;
  }
  const encoder::Snapshot& snapshot() const { return c_.snapshot(); }
  template <class Done>
  bool drive(Done&& done, link::Duration timeout = link::Duration::zero()) {
    return c_.drive(std::forward<Done>(done), timeout);
  }

  int set_address() {
    if (!session_.set_slave_address(static_cast<std::uint8_t>(options_.value)))
      return refuse("set the address");
    if (!drive([&] { return session_.address_change_status() != profibus::RequestStatus::pending; }))
      return failed_to("answer Set_Slave_Add at station 126");
    if (session_.address_change_status() != profibus::RequestStatus::done) {
      // The request ended before the time-out: refused, or no station 126 answered its retries.
      if (session_.health().error_replies > 0) {
        spdlog::error(
            "encoder on {}: the station at address 126 refused Set_Slave_Add (its address may be locked); "
            "it keeps address 126",
            c_.path());
        return kExitFailed;
      }
      spdlog::error(
          "encoder on {}: no encoder answers at address 126 ({} tries): set-address only reaches an encoder "
          "whose address switches are at 126 (manual 3.4). An encoder that answers at another address needs "
          "no new one: set station_address in the config and check with `cellctl encoder status`; else check "
          "the cable and the port",
          c_.path(), session_.health().retries + 1);
      return kExitLink;
    }
    fmt::print(
        "encoder now answers at station {} (stored in its EEPROM); set station_address: {} in the config\n",
        options_.value, options_.value);
    return kExitOk;
  }

  int teach_in() {
    if (!session_.teach_in_start())
      return refuse("start Teach-In (needs status bits and commissioning: true)");
    if (!finish_command()) return failed_to("start Teach-In");
    session_.clear_command();
    fmt::print(
        "Teach-In started at {} (un-scaled). Move the axis to the end point without crossing the\n"
        "encoder's zero, then press Enter.\n",
        snapshot().position_counts);
    if (!drive(enter_pressed, 3600s)) return failed_to("see Enter");
    if (!session_.teach_in_end(options_.value)) return refuse("end Teach-In");
    if (!finish_command()) return failed_to("end Teach-In");
    fmt::print(
        "total resolution {}: enter it as measuring_units (units_select: per_total_range) in the config\n",
        snapshot().command.result);
    print_status(session_);
    return kExitOk;
  }

  bool finish_command() {
    if (!drive([&] { return snapshot().command.phase >= encoder::Handshake::Phase::done; })) return false;
    if (snapshot().command.phase == encoder::Handshake::Phase::failed) {
      spdlog::error("encoder: {}", snapshot().command.failure);
      return false;
    }
    return true;
  }

  // The session's state or the configured parameters stand in the way, not the command line.
  int refuse(const char* what) const { return c_.refuse(what); }

  int failed_to(const char* what) const {
    // A start-up the encoder refused (or the parameters refused here) is a failure, not a lost link; a
    // time-out without data exchange is one.
    const bool refused =
        snapshot().startup_fault != profibus::StartupFault::Kind::none || snapshot().local_prm_violation;
    const bool timed_out_exchanging =
        snapshot().data_exchange || snapshot().command.phase == encoder::Handshake::Phase::failed;
    const int code = c_.failed_to(what, timed_out_exchanging ? kExitFailed : kExitLink);
    return code == kExitLink && c_.faulted() && refused ? kExitFailed : code;
  }

  const EncoderOptions& options_;
  Commissioning<encoder::Session> c_;
  encoder::Session& session_ = c_.session();
};

int run_encoder(const GlobalOptions& global, const EncoderOptions& options, Action action) {
  const auto cell = config::load_cell_config(global.config);
  if (!cell.encoder) {
    spdlog::error("{} has no encoder: section (the parameters and scaling come from there)", global.config);
    return kExitConfig;
  }
  EncoderCommissioning commissioning(global, options, *cell.encoder, action);
  return commissioning.run(action);
}

}  // namespace

void add_encoder_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<EncoderOptions>();
  DeviceGroup group(app, "encoder", "Commission the Scancon SCH88BEX encoder (PROFIBUS DP, 8E1)", *options,
                    "Seconds to wait for the encoder");
  auto add = [&](const char* name, const char* help, Action action) {
    auto* sub = group.add_action(name, help);
    commands.on(sub, [&commands, options, action] { return run_encoder(commands.global, *options, action); });
    return sub;
  };
  add("status", "Start the encoder up and print position, velocity and status bits", Action::status);
  add("diag", "Print status and the decoded diagnosis (alarms, warnings, resolution, versions, …)",
      Action::diag);
  auto* preset = add("preset", "Preset the position to a value (in measuring units)", Action::preset);
  preset->add_option("value", options->value, "New position in measuring units")->required();
  auto* direction =
      add("direction", "Change the counting direction on the fly (commissioning mode)", Action::direction);
  direction->add_option("sequence", options->direction, "cw or ccw: the direction in which counts increase")
      ->required()
      ->check(CLI::IsMember({"cw", "ccw"}));
  auto* address =
      add("set-address", "Give an encoder at station 126 a new address (Set_Slave_Add)", Action::set_address);
  address->add_option("address", options->value, "New station address")
      ->required()
      ->check(CLI::Range(1, 125));
  auto* teach =
      add("teach-in", "Teach-In: start here, move to the end point, press Enter, get the total resolution",
          Action::teach_in);
  teach->add_option("--distance", options->value, "The travelled distance in desired units")
      ->required()
      ->check(CLI::Range(1, (1 << 25) - 1));
}

}  // namespace cellctl::cli
