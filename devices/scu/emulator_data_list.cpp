// scu::Emulator: its data list — RG reads a value (counters, currents, status, the user positions,
// the remote data), RT writes one (only the remote data 0x3xxx is writable), each checked whole
// before anything changes.
#include <algorithm>
#include <cmath>
#include <string>

#include "scu/data_list.hpp"
#include "scu/emulator.hpp"
#include "wire/byte_reader.hpp"

namespace cellctl::scu {
namespace {

std::uint16_t percent(double part, double whole) noexcept {
  if (whole <= 0.0) return 0;
  return static_cast<std::uint16_t>(std::lround(std::clamp(part / whole, 0.0, 1.0) * 100.0));
}

}  // namespace

Status Emulator::handle(const GetRequest& r, wire::ByteWriter& out) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  return read_value(r.data_id, out) && out.ok() ? Status::ack : Status::parameter_data_error;
}

Status Emulator::handle(const TransferRequest& r) {
  if (const auto s = remote_permission(); s != Status::ack) return s;
  const auto s = check_write(r.data_id, r.value);
  if (s == Status::ack) apply_write(r.data_id, r.value);
  return s;
}

bool Emulator::read_value(std::uint16_t id, wire::ByteWriter& out) const {
  const auto elements = elements_of(id);
  if (elements.empty()) return false;
  for (const auto& e : elements) read_element(e.id, out);
  return true;
}

void Emulator::read_element(std::uint16_t id, wire::ByteWriter& out) const {
  const int low = id & 0x0F;  // actuator / function / history number inside a block
  const auto a = static_cast<std::size_t>(std::clamp(low, 1, kActuatorCount) - 1);
  const bool is_present = low >= 1 && low <= kActuatorCount && config_.actuators[a].present;
  const auto& phys = config_.actuators[a].physics;
  const auto string_of = [&](const std::string& s, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i) out.u8(i < s.size() ? static_cast<std::uint8_t>(s[i]) : 0);
  };
  const auto current = [&]() -> std::uint16_t {  // 0.1 A: 2 A idle draw of a running motor, + load with speed
    if (!is_present || !actuators_[a].moving()) return 0;
    return static_cast<std::uint16_t>(
        20 + percent(std::abs(actuators_[a].velocity_mm_s()), phys.max_speed_mm_s) / 2);
  };
  switch (id & 0xFFF0) {
    case 0x0000:
      string_of(id == data_id::kFirmwareInfo ? config_.firmware : config_.configuration, value_size(id));
      return;
    case 0x0010:
      out.le(position_edges(low));
      return;
    case 0x0030:
      out.le(std::uint16_t{0});
      return;
    case 0x0060:
      out.le(is_present ? relay_in_[a] : 0u);
      return;
    case 0x0070:
      out.le(is_present ? relay_out_[a] : 0u);
      return;
    case 0x0080:
      out.le(id == 0x008F ? over_current_count_ : is_present ? actuator_errors_[a] : 0u);
      return;
    case 0x0090:
      out.le(is_present ? static_cast<std::uint32_t>(stroke_edges_[a]) : 0u);
      return;
    case 0x00A0:
      out.le(current());
      return;
    case 0x00B0: {
      std::uint16_t total = 0;
      for (auto m : max_current_) total = std::max(total, m);
      out.le(id == 0x00BF ? total : std::max(max_current_[a], current()));
      return;
    }
    case 0x00C0:
      if (id == 0x00C0)
        out.u8(40);
      else
        out.le(std::uint32_t{0});
      return;
    case 0x00D0:
      out.le(error_codes_[static_cast<std::size_t>(low - 1)]);
      return;
    case 0x00E0:
      out.u8(Status2{is_present && initialised_[a], is_present, is_present}.to_byte());
      return;
    case 0x00F0:
      out.le(is_present ? percent(std::abs(actuators_[a].velocity_mm_s()), phys.max_speed_mm_s)
                        : std::uint16_t{0});
      return;
    case 0x0160:
      if (id == 0x0166)
        out.u8(1);  // user 1
      else if (id == 0x0165)
        out.u8(0);  // no locking box
      else
        out.le(std::uint16_t{0});  // nothing locked, no battery
      return;
    case 0x0170:
      out.u8(status1(low).to_byte());
      return;
    case 0x1010:
      out.le_float(is_present ? static_cast<float>(1.0 / config_.actuators[a].edges_per_mm) : 0.0f);
      return;
    case 0x2000: {
      const double scale = is_present ? phys.stroke_mm * config_.actuators[a].edges_per_mm : 0.0;
      for (int user = 0; user < 4; ++user)
        for (double f : kUserPositionFractions) out.le(static_cast<std::int32_t>(std::lround(f * scale)));
      out.le(std::int32_t{0});
      out.le(static_cast<std::int32_t>(std::lround(scale)));
      return;
    }
    case 0x3000:
      for (auto v : cyclic_objects_[static_cast<std::size_t>(low - 1)]) out.le(v);
      return;
    case 0x3010:
      out.le(remote_speed_[static_cast<std::size_t>(low - 1)]);
      return;
    case 0x3020:
      out.le(remote_position_[a]);
      return;
    default:
      break;
  }
  switch (id) {
    case 0x0020:
      out.u8(0);
      return;
    case 0x0040:
      out.le(std::uint32_t{0});
      return;
    case 0x0100:
      out.u8(0x01);
      return;  // mains connected
    case 0x0110:
      out.u8(outputs_);
      return;
    case 0x0120:
      out.u8(hand_switch_leds_);
      return;
    case 0x0130:
      out.u8(0);
      return;
    case 0x0140:
      out.u8(buzzer_);
      return;
    case 0x0150:
      out.u8(1);
      return;  // sensor supply on
    default:
      break;
  }
  for (std::size_t i = 0; i < value_size(id); ++i)
    out.u8(0);  // unreachable for listed IDs; keeps sizes right
}

Status Emulator::check_write(std::uint16_t id, std::span<const std::uint8_t> value) const {
  const auto elements = elements_of(id);
  if (elements.empty()) return Status::parameter_data_error;
  if (!is_remote_data(id)) return Status::permission_error;  // only 0x3xxx is writable
  if (value.size() != value_size(id)) return Status::parameter_count_error;
  wire::ByteReader r(value);
  for (const auto& e : elements) {
    if (e.type == DataType::cyclic_object) {
      for (std::size_t i = 0; i < 12; ++i) {
        const auto ref = r.le<std::uint16_t>();
        if (ref == kUnusedDataId) continue;
        if (value_size(ref) == 0) return Status::parameter_data_error;
        if (i < 6 && !is_remote_data(ref)) return Status::parameter_data_error;  // write IDs must be 3xxx
      }
    } else if ((e.id & 0xFFF0) == 0x3010) {
      if (r.le<std::uint16_t>() > 100) return Status::parameter_data_error;  // speed in %
    } else {
      (void)r.bytes(size_of(e.type));  // skipped: any other value is taken as it is
    }
  }
  return Status::ack;
}

void Emulator::apply_write(std::uint16_t id, std::span<const std::uint8_t> value) {
  wire::ByteReader r(value);
  for (const auto& e : elements_of(id)) {
    const auto low = static_cast<std::size_t>((e.id & 0x0F) - 1);
    if (e.type == DataType::cyclic_object) {
      for (auto& v : cyclic_objects_[low]) v = r.le<std::uint16_t>();
    } else if ((e.id & 0xFFF0) == 0x3010) {
      remote_speed_[low] = r.le<std::uint16_t>();
      // A speed change during the motion: the SCU adjusts the speed keeping the ramp.
      const auto& fn = config_.functions[low];
      for (int a = 1; a <= kActuatorCount; ++a) {
        if (!fn.moves(a) || owner_[index(a)] != static_cast<int>(low)) continue;
        actuators_[index(a)].set_speed(remote_speed_[low] / 100.0 *
                                       config_.actuators[index(a)].physics.max_speed_mm_s);
      }
    } else if ((e.id & 0xFFF0) == 0x3020) {
      remote_position_[low] = r.le<std::int32_t>();
    }
  }
}

}  // namespace cellctl::scu
