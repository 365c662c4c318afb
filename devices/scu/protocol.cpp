#include "scu/protocol.hpp"

namespace cellctl::scu {

std::optional<Command> command_from_byte(std::uint8_t b) noexcept {
  switch (b) {
    case 'G':
      return Command::get;
    case 'T':
      return Command::transfer;
    case 'C':
      return Command::cyclic;
    case 'E':
      return Command::execute;
    case 'S':
      return Command::stop;
    case 'O':
      return Command::open;
    case 'A':
      return Command::abort;
    default:
      return std::nullopt;
  }
}

std::optional<Status> status_from_byte(std::uint8_t b) noexcept {
  switch (b) {
    case 0x06:
      return Status::ack;
    case 0x80:
      return Status::checksum_error;
    case 0x81:
      return Status::parameter_data_error;
    case 0x82:
      return Status::parameter_count_error;
    case 0x83:
      return Status::invalid_command;
    case 0x84:
      return Status::permission_error;
    default:
      return std::nullopt;
  }
}

std::string_view to_string(Command c) noexcept {
  switch (c) {
    case Command::get:
      return "RG";
    case Command::transfer:
      return "RT";
    case Command::cyclic:
      return "RC";
    case Command::execute:
      return "RE";
    case Command::stop:
      return "RS";
    case Command::open:
      return "RO";
    case Command::abort:
      return "RA";
  }
  return "R?";
}

std::string_view to_string(Status s) noexcept {
  switch (s) {
    case Status::ack:
      return "ACK";
    case Status::checksum_error:
      return "CSE";
    case Status::parameter_data_error:
      return "PDE";
    case Status::parameter_count_error:
      return "PCE";
    case Status::invalid_command:
      return "ICE";
    case Status::permission_error:
      return "PE";
  }
  return "?";
}

std::string_view describe(Status s) noexcept {
  switch (s) {
    case Status::ack:
      return "accepted";
    case Status::checksum_error:
      return "checksum error in the request";
    case Status::parameter_data_error:
      return "a parameter value is not valid";
    case Status::parameter_count_error:
      return "wrong number of parameter bytes";
    case Status::invalid_command:
      return "unknown command";
    case Status::permission_error:
      return "not permitted in the SCU's current mode or state";
  }
  return "unknown status";
}

}  // namespace cellctl::scu
