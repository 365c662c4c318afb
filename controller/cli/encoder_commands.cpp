#include "cli/encoder_commands.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <optional>
#include <string>

#include "cli/commissioning.hpp"
#include "cli/encoder_status.hpp"
#include "config/cell_config.hpp"
#include "config/config_edit.hpp"
#include "device_seam/device_registry.hpp"
#include "encoder/commissioning_parameters.hpp"
#include "encoder/session.hpp"
#include "exit_codes/exit_codes.hpp"
#include "runtime/dry_run_state.hpp"

namespace cellctl::cli {
namespace {

using namespace std::chrono_literals;

enum class EncoderAction { status, diag, preset, direction, set_address };

struct EncoderOptions : DeviceOptions {
  EncoderOptions() { timeout_s = 10.0; }
  std::uint32_t value = 0;  // preset value or new address
  std::string direction = "cw";
  std::optional<std::string> write_config;  // preset, direction: record the change in this file
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
  fmt::print("{}", encoder_input_lines(session.lifecycle(), s));
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

// Where a preset or a direction change is recorded. It lives in the encoder's EEPROM and changes every
// position the next run reads, so it belongs in the config's encoder section, where every run's
// start-up checks it — but only in the config of the encoder that was changed: a command that talked
// to another port than the config names (--port: an emulator's pseudo-terminal, a bench encoder) is a
// rehearsal, and a config that names hardware ports is never rewritten from it. Its change goes to the
// dry-run copy <state_dir>/config.dry-run.yaml instead, printed, unless --write-config names the file
// deliberately.
struct ConfigTarget {
  std::filesystem::path config;             // the cell's config (-c)
  std::filesystem::path state_dir;          // the cell's state folder, for the dry-run copy
  bool talked_to_configured = true;         // the command used the port the config names
  std::optional<std::string> write_config;  // --write-config FILE
};

int record(const ConfigTarget& target, const std::vector<config::KeyChange>& changes) {
  const bool own = target.write_config || target.talked_to_configured;
  const std::filesystem::path file =
      target.write_config ? std::filesystem::path(*target.write_config) : target.config;
  try {
    if (own) {
      const auto change = config::change_config_file(file, "encoder", changes);
      for (const auto& line : change.changed) fmt::print("config         {}\n", line);
      fmt::print("config         {} written (the previous one kept as {})\n", file.string(),
                 change.backup.string());
      return kExitOk;
    }
    const auto copy = runtime::dry_run_config_file(target.state_dir);
    const auto change = config::change_config_copy(target.config, copy, "encoder", changes);
    for (const auto& line : change.changed) fmt::print("dry run        {}\n", line);
    fmt::print(
        "dry run        {} is left as it was: this encoder is not on the port it names (--port). The change "
        "is in {}; to record it in a config deliberately: the same command with --write-config FILE\n",
        target.config.string(), copy.string());
    return kExitOk;
  } catch (const std::exception& e) {
    spdlog::error(
        "the encoder was changed but {} could not be updated: {}. Until it is, every run refuses the encoder "
        "at start",
        (own ? file : runtime::dry_run_config_file(target.state_dir)).string(), e.what());
    return kExitFailed;
  }
}

class EncoderCommissioning {
 public:
  EncoderCommissioning(const GlobalOptions& global, const EncoderOptions& options,
                       const config::CellConfig& cell, EncoderAction action)
      : options_(options),
        target_{global.config, cell.state_dir, talks_to_configured(options, cell.encoder->port),
                options.write_config},
        c_(global, options, cell.encoder->port, "encoder", session_config(cell.encoder->session, action)) {}

  int run(EncoderAction action) {
    // A preset beyond this encoder's scaling is a bad argument (manual 4.3.2): refused before the bus.
    if (const auto range = session_.scaling().range();
        action == EncoderAction::preset && options_.value >= range) {
      spdlog::error("preset {}: must be 0 … {} (the total measuring range − 1)", options_.value, range - 1);
      return kExitUsage;
    }
    if (action == EncoderAction::direction)
      if (const auto why = encoder::manufacturer_functions_unavailable(session_.config().parameters);
          !why.empty()) {
        spdlog::error("encoder direction: {}; set code_sequence in the config's encoder section instead",
                      why);
        return kExitFailed;
      }
    c_.activate();
    if (action == EncoderAction::set_address) return set_address();
    if (!drive([&] { return snapshot().data_exchange && snapshot().exchanges > 2; }))
      return failed_to("exchange data");
    switch (action) {
      case EncoderAction::preset:
        if (!session_.preset(options_.value)) return refuse("preset");
        if (!finish_command()) return failed_to("acknowledge the preset");
        return record_offset();
      case EncoderAction::direction:
        if (!session_.set_direction(options_.direction == "ccw" ? encoder::CodeSequence::ccw
                                                                : encoder::CodeSequence::cw))
          return refuse("change direction");
        if (!finish_command()) return failed_to("acknowledge the direction change");
        print_status(session_);
        fmt::print(
            "note           positions now count the other way round: set zero_offset_mm (or preset) so that "
            "the "
            "axis reads its position before a run\n");
        // Set_Prm sends code_sequence at every start-up (4.1.1 octet 9 bit 0): recorded there, the change
        // lasts; the encoder is left in the configured (normal) mode at the next start-up.
        return record(target_, {{"code_sequence", options_.direction}});
      default:
        break;
    }
    (void)c_.drive_for(20ms);  // a few exchanges for a fresh status: a fault in them shows in it
    print_status(session_);
    if (action == EncoderAction::diag) print_diag(snapshot());
    if (const auto& d = snapshot().diagnosis; d && d->detail && d->detail->offset != configured_offset_)
      fmt::print(
          "WARNING        the encoder holds preset offset {}, the config expects preset_offset: {}: a run "
          "refuses this encoder at start\n",
          d->detail->offset, configured_offset_);
    // A bus in data exchange whose inputs are no positions is no working encoder: said, and not exit 0.
    if (!encoder_inputs_valid(snapshot())) {
      spdlog::error("encoder on {}: its inputs are not valid positions ({})", c_.path(),
                    snapshot().input_fault.empty() ? "none valid" : snapshot().input_fault);
      return kExitFailed;
    }
    return kExitOk;
  }

 private:
  encoder::SessionConfig session_config(encoder::SessionConfig c, EncoderAction action) {
    // Commissioning reads and changes the stored offset: it is compared here, not refused.
    configured_offset_ = c.expected_offset.value_or(0);
    c.expected_offset.reset();
    // Set_Slave_Add is only possible for an encoder whose switches are at 126 (manual 3.4).
    if (action == EncoderAction::set_address) c.station_address = 126;
    // A direction change on the fly needs commissioning mode (4.4): switched on for this command only.
    if (action == EncoderAction::direction) c.parameters = encoder::commissioning_parameters(c.parameters);
    return c;
  }

  // The encoder reports its new offset in its diagnosis (4.2.14), read at start-up: started again to
  // read it, then recorded in the config.
  int record_offset() {
    session_.deactivate(c_.clock().now());
    if (!drive([&] { return session_.lifecycle() == link::Lifecycle::inactive; }))
      return failed_to("close after the preset");
    const auto reads = snapshot().diagnosis_reads;
    c_.activate();
    if (!drive([&] { return snapshot().data_exchange && snapshot().diagnosis_reads > reads; }))
      return failed_to("start up again after the preset");
    print_status(session_);
    const auto& d = snapshot().diagnosis;
    if (!d || !d->detail) {
      spdlog::error(
          "encoder: preset done, but its diagnosis carries no offset (short_diagnosis: true?): set "
          "preset_offset in the config's encoder section by hand from `cellctl encoder diag` with "
          "short_diagnosis: false");
      return kExitFailed;
    }
    return record(target_, {{"preset_offset", std::to_string(d->detail->offset)}});
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

  // --port names the configured port, or the pseudo-terminal `cellctl emulate` publishes for it.
  static bool talks_to_configured(const EncoderOptions& o, const config::PortConfig& port) {
    if (!o.port) return true;
    return *o.port == (port.emulated() ? port.publish_as : port.port);
  }

  const EncoderOptions& options_;
  ConfigTarget target_;
  std::int32_t configured_offset_ = 0;
  Commissioning<encoder::Session> c_;
  encoder::Session& session_ = c_.session();
};

int run_encoder(const GlobalOptions& global, const EncoderOptions& options, EncoderAction action) {
  const auto cell = device_seam::load_cell_config(global.config);
  if (!cell.encoder) {
    spdlog::error("{} has no encoder: section (the parameters and scaling come from there)", global.config);
    return kExitConfig;
  }
  EncoderCommissioning commissioning(global, options, cell, action);
  return commissioning.run(action);
}

}  // namespace

void add_encoder_commands(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<EncoderOptions>();
  DeviceGroup group(app, "encoder", "Commission the Scancon SCH88BEX encoder (PROFIBUS DP, 8E1)", *options,
                    "Seconds to wait for the encoder");
  auto add = [&](const char* name, const char* help, EncoderAction action) {
    auto* sub = group.add_action(name, help);
    commands.on(sub, [&commands, options, action] { return run_encoder(commands.global, *options, action); });
    return sub;
  };
  add("status", "Start the encoder up and print position, velocity and status bits", EncoderAction::status);
  add("diag", "Print status and the decoded diagnosis (alarms, warnings, resolution, versions, …)",
      EncoderAction::diag);
  auto* preset = add("preset",
                     "Preset the position to a value (in measuring units); the encoder's new offset is "
                     "recorded as preset_offset in the config (backup: FILE.bak), which every run checks",
                     EncoderAction::preset);
  preset->add_option("value", options->value, "New position in measuring units")->required();
  const char* write_config_help =
      "Record the change in this config file (backup FILE.bak) even though the encoder was reached on "
      "another port than the config names (without it such a change goes to <state_dir>/config.dry-run.yaml)";
  preset->add_option("--write-config", options->write_config, write_config_help);
  auto* direction =
      add("direction",
          "Change the counting direction on the fly (the encoder is put in commissioning mode for it) and "
          "record it as code_sequence in the config (backup: FILE.bak)",
          EncoderAction::direction);
  direction->add_option("sequence", options->direction, "cw or ccw: the direction in which counts increase")
      ->required()
      ->check(CLI::IsMember({"cw", "ccw"}));
  direction->add_option("--write-config", options->write_config, write_config_help);
  auto* address = add("set-address", "Give an encoder at station 126 a new address (Set_Slave_Add)",
                      EncoderAction::set_address);
  address->add_option("address", options->value, "New station address")
      ->required()
      ->check(CLI::Range(1, 125));
}

}  // namespace cellctl::cli
