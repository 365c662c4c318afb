// spindle::Emulator driven with raw telegrams: what it answers, what it leaves unanswered, its hour
// counters and its fault history — the converter behaviour the session relies on.

#include "spindle/emulator.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "link/sim_link.hpp"
#include "spindle/fault_numbers.hpp"

namespace cellctl::spindle {
namespace {

using namespace std::chrono_literals;

class EmulatorRaw : public ::testing::Test {
 protected:
  // Sends one message (or raw bytes) and returns every frame the emulator answered within 100 ms.
  std::vector<Decoded> exchange(std::span<const std::uint8_t> bytes) {
    (void)sim.master().write(bytes);
    std::vector<Decoded> answers;
    for (int i = 0; i < 100; ++i) {
      emulator.poll(clock.now());
      std::array<std::uint8_t, 256> buf{};
      const auto r = sim.master().read(buf);
      for (std::size_t k = 0; k < r.count; ++k)
        if (auto d = decoder.push(buf[k])) answers.push_back(*d);
      clock.advance(1ms);
    }
    return answers;
  }
  std::vector<Decoded> send(const Message& m) {
    std::array<std::uint8_t, kMaxFrameLength> frame{};
    return exchange(std::span(frame).first(Codec::encode(m, frame)));
  }
  Message ask(MsgId what) {
    const auto answers = send(Request{what});
    EXPECT_EQ(answers.size(), 1u);
    return answers.empty() ? Message{} : answers[0].message;
  }

  link::VirtualClock clock;
  link::SimLink sim{clock, link::line_8n1(38400), "sim"};
  EmulatorConfig config = [] {
    EmulatorConfig c;
    c.converter_hours = 10.0;
    c.motor_hours = 2.5;
    return c;
  }();
  Emulator emulator{sim.device(), config};
  FrameDecoder decoder;
};

TEST_F(EmulatorRaw, AcknowledgesEverySetAndCommandWithItsId) {
  for (const Message m :
       {Message{SetStart{}}, Message{SetBasic{400, SpeedUnit::hz}}, Message{Command{MsgId::cmd_start}},
        Message{Command{MsgId::cmd_stop}}, Message{Command{MsgId::cmd_reset}}}) {
    const auto answers = send(m);
    ASSERT_EQ(answers.size(), 1u);
    EXPECT_EQ(answers[0].message, Message{Ack{id_of(m)}});
  }
}

TEST_F(EmulatorRaw, KeepsSilentOnBadChecksumUnknownIdAndItsOwnMessages) {
  const std::uint8_t bad_checksum[] = {kStx, '0', '1', 'c', 'f', '0', '1', '5', '9', 'f', '8', kEtx};
  EXPECT_TRUE(exchange(bad_checksum).empty());
  const std::uint8_t unknown_id[] = {kStx, '0', '1', 'c', 'c', '0', '1', '5', '9', 'f', '6', kEtx};
  EXPECT_TRUE(exchange(unknown_id).empty());
  EXPECT_TRUE(send(Ack{MsgId::cmd_start}).empty());
  EXPECT_TRUE(send(StatusOut{}).empty());
  EXPECT_EQ(emulator.frames_rejected(), 2u);
  EXPECT_EQ(send(Request{MsgId::res_statusout}).size(), 1u);  // and it is still there
}

TEST_F(EmulatorRaw, RefusesToStartUntilTheSourcesAreSycoDrive) {
  (void)send(SetBasic{400, SpeedUnit::hz});
  (void)send(Command{MsgId::cmd_start});
  auto s = std::get<StatusOut>(ask(MsgId::res_statusout));
  EXPECT_EQ(s.state, DeviceState::warning);
  EXPECT_EQ(s.error_number, kWarningStartSourceNotRs232);
  EXPECT_TRUE(s.at_rest());
  EXPECT_EQ(s.flags & StatusOut::kAtRestFlags, StatusOut::kAtRestFlags);  // both STILLSTAND bits

  (void)send(SetStart{Source::sycodrive, Source::digital_input, Direction::clockwise});
  (void)send(Command{MsgId::cmd_start});
  EXPECT_EQ(std::get<StatusOut>(ask(MsgId::res_statusout)).error_number, kWarningStartSourceNotRs232);

  (void)send(SetStart{Source::sycodrive, Source::sycodrive, Direction::clockwise});
  (void)send(Command{MsgId::cmd_start});
  s = std::get<StatusOut>(ask(MsgId::res_statusout));
  EXPECT_EQ(s.state, DeviceState::none);
  EXPECT_FALSE(s.at_rest());
  EXPECT_GT(emulator.motor().frequency_hz(), 0.0);
}

TEST_F(EmulatorRaw, CountsOperatingHoursOfConverterAndMotor) {
  emulator.poll(clock.now());
  clock.advance(std::chrono::hours(1));
  emulator.poll(clock.now());  // an hour at rest: only the converter counts
  auto v = std::get<StatusValues>(ask(MsgId::res_status));
  EXPECT_EQ(v.converter_hours, 11u);
  EXPECT_EQ(v.motor_hours, 2u);

  (void)send(SetStart{});
  (void)send(SetBasic{400, SpeedUnit::hz});
  (void)send(Command{MsgId::cmd_start});
  clock.advance(std::chrono::minutes(30));
  emulator.poll(clock.now());
  v = std::get<StatusValues>(ask(MsgId::res_status));
  EXPECT_EQ(v.converter_hours, 11u);  // 11.5 h
  EXPECT_EQ(v.motor_hours, 3u);       // 2.5 h + 0.5 h
}

TEST_F(EmulatorRaw, KeepsTheLastFiveFaultsNewestFirst) {
  for (int n = 1; n <= 6; ++n) {
    emulator.inject_fault(static_cast<std::uint8_t>(n));
    (void)send(Command{MsgId::cmd_reset});
  }
  const auto id = std::get<Identification>(ask(MsgId::res_ident));
  EXPECT_EQ(std::vector<int>(std::begin(id.fault_history), std::end(id.fault_history)),
            (std::vector<int>{6, 5, 4, 3, 2}));
  EXPECT_EQ(id.converter_type, config.converter_type);
  EXPECT_EQ(id.firmware, config.firmware);
}

TEST_F(EmulatorRaw, LiveValuesRiseWithFrequency) {
  (void)send(SetStart{});
  (void)send(SetBasic{1000, SpeedUnit::hz});  // still running up after the 2 s sampled here
  (void)send(Command{MsgId::cmd_start});
  std::uint16_t last_power = 0, last_voltage = 0;
  for (int i = 0; i < 5; ++i) {
    clock.advance(300ms);
    emulator.poll(clock.now());
    const auto v = std::get<StatusValues>(ask(MsgId::res_status));
    EXPECT_GT(v.power_dw, last_power);
    EXPECT_GT(v.motor_voltage_cv, last_voltage);
    last_power = v.power_dw;
    last_voltage = v.motor_voltage_cv;
  }
}

}  // namespace
}  // namespace cellctl::spindle
