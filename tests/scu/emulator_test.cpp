// scu::Emulator driven telegram by telegram from the master end of a SimLink: the remote-mode state
// machine, the watchdog, the error replies, the data list, and fault injection.

#include "scu/emulator.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "scu/data_list.hpp"
#include "scu/reply_stream.hpp"
#include "scu_rig.hpp"
#include "wire/byte_writer.hpp"
#include "wire/hex.hpp"

namespace cellctl::scu {
namespace {

using namespace std::chrono_literals;

struct Answer {
  Status status = Status::ack;
  std::vector<std::uint8_t> data;
};

class RawMaster {
 public:
  RawMaster() : emulator(sim.device(), scp11_emulator(2, testing::test_physics(), 100.0)) {}

  // Sends raw bytes and steps until the reply to `shape` is complete (nullopt after 500 ms).
  std::optional<Answer> send_raw(std::span<const std::uint8_t> bytes, ReplyShape shape) {
    stream.expect(shape);
    (void)sim.master().write(bytes);
    std::optional<Answer> got;
    cellctl::testing::run_until(
        clock, 100us, 500ms,
        [&](link::TimePoint t) {
          emulator.poll(t);
          std::array<std::uint8_t, 64> buf{};
          const auto r = sim.master().read(buf);
          (void)stream.feed(std::span(buf).first(r.count));
          for (auto e = stream.next(); e.kind != ReplyStream::Event::Kind::need_more; e = stream.next())
            if (e.kind == ReplyStream::Event::Kind::reply)
              got = Answer{e.reply.status, {e.reply.data.begin(), e.reply.data.end()}};
        },
        [&] { return got.has_value(); });
    return got;
  }
  std::optional<Answer> send(const Request& r) {
    RequestBytes bytes;
    EXPECT_TRUE(encode_request(r, bytes));
    return send_raw(bytes.view(), reply_shape(r));
  }
  Status status_of(const Request& r) {
    const auto a = send(r);
    return a ? a->status : static_cast<Status>(0);
  }
  void open_remote(std::uint8_t safety_id = 0) {
    ASSERT_EQ(status_of(OpenRequest{safety_id}), Status::ack);
    ASSERT_EQ(status_of(CyclicRequest{}), Status::ack);
  }
  void idle(link::Duration d) {
    cellctl::testing::run_for(clock, 1ms, d, [&](link::TimePoint t) { emulator.poll(t); });
  }
  template <class T>
  static std::vector<std::uint8_t> le(T v) {
    std::vector<std::uint8_t> out(sizeof(T));
    wire::ByteWriter w(out);
    w.le(v);
    return out;
  }

  link::VirtualClock clock;
  link::SimLink sim{clock, link::line_8n1(38400), "scu"};
  Emulator emulator;
  ReplyStream stream;
};

TEST(ScuEmulator, RemoteCommandsNeedRoThenRc) {
  RawMaster m;
  EXPECT_EQ(m.status_of(GetRequest{0x0011}), Status::permission_error) << "not in remote mode";
  EXPECT_EQ(m.status_of(CyclicRequest{}), Status::permission_error) << "RC before RO";
  EXPECT_EQ(m.status_of(OpenRequest{0}), Status::ack);
  EXPECT_EQ(m.status_of(GetRequest{0x0011}), Status::permission_error) << "RC must come before anything else";
  EXPECT_EQ(m.status_of(CyclicRequest{}), Status::ack);
  EXPECT_EQ(m.status_of(GetRequest{0x0011}), Status::ack);
  EXPECT_EQ(m.status_of(AbortRequest{}), Status::ack);
  EXPECT_FALSE(m.emulator.remote_open());
  EXPECT_EQ(m.status_of(GetRequest{0x0011}), Status::permission_error);
}

TEST(ScuEmulator, KeepAliveSilenceStopsTheMotionAndSetsBit22) {
  RawMaster m;
  m.open_remote(0);
  const auto speed = RawMaster::le<std::uint16_t>(100);
  const auto pos = RawMaster::le<std::int32_t>(15000);
  ASSERT_EQ(m.status_of(TransferRequest{0x3011, speed}), Status::ack);
  ASSERT_EQ(m.status_of(TransferRequest{0x3021, pos}), Status::ack);
  ASSERT_EQ(m.status_of(ExecuteRequest{0, 9, kSoftStartStop}), Status::ack);
  const auto last_rc = m.clock.now();  // the RC above came just before; from now on: silence
  m.idle(400ms);
  EXPECT_TRUE(m.emulator.actuator(1).moving()) << "still inside the watchdog";
  EXPECT_FALSE(m.emulator.error_word().remote_timeout());
  m.idle(200ms);
  EXPECT_GT(m.clock.now() - last_rc, 500ms);
  EXPECT_FALSE(m.emulator.actuator(1).active()) << "watchdog lapse stops the motion";
  EXPECT_TRUE(m.emulator.error_word().remote_timeout());
  EXPECT_TRUE(m.emulator.watchdog_lapsed());
  // Safety_ID 0: only RC, RA, RO are accepted now; the error word still reads through RC with an object.
  EXPECT_EQ(m.status_of(GetRequest{0x00D1}), Status::permission_error);
  EXPECT_EQ(m.status_of(CyclicRequest{}), Status::ack);
  EXPECT_EQ(m.status_of(ExecuteRequest{0, 9, kSoftStartStop}), Status::permission_error);
  EXPECT_EQ(m.status_of(OpenRequest{0}), Status::ack);
  EXPECT_FALSE(m.emulator.error_word().remote_timeout()) << "RO clears bit 22";
}

TEST(ScuEmulator, AnRcThatArrivedInTimeKeepsRemoteModeEvenWhenTheEmulatorPollsLate) {
  // The emulator's thread may be kept off the CPU: what has arrived is read before the lapse is judged.
  RawMaster m;
  m.open_remote();
  m.idle(400ms);
  RequestBytes rc;
  ASSERT_TRUE(encode_request(CyclicRequest{}, rc));
  ASSERT_EQ(m.sim.master().write(rc.view()).count, rc.size());  // at 400 ms: in time
  m.clock.advance(300ms);  // the next poll comes 700 ms after the last one it answered
  m.emulator.poll(m.clock.now());
  EXPECT_FALSE(m.emulator.watchdog_lapsed());
  EXPECT_FALSE(m.emulator.error_word().remote_timeout());
}

TEST(ScuEmulator, SafetyId1ResumesWithTheNextRc) {
  RawMaster m;
  m.open_remote(1);
  m.idle(600ms);
  EXPECT_TRUE(m.emulator.watchdog_lapsed());
  EXPECT_EQ(m.status_of(CyclicRequest{}), Status::ack);
  EXPECT_EQ(m.status_of(GetRequest{0x00D1}), Status::ack);
  EXPECT_EQ(m.send(GetRequest{0x00D1})->data, RawMaster::le<std::uint32_t>(1u << 21)) << "bit 22 reported";
}

TEST(ScuEmulator, ErrorRepliesForBadParameters) {
  RawMaster m;
  EXPECT_EQ(m.status_of(OpenRequest{3}), Status::parameter_data_error) << "Safety_ID 0..2";
  m.open_remote();
  EXPECT_EQ(m.status_of(GetRequest{0x0017}), Status::parameter_data_error) << "no such ID";
  const auto pos = RawMaster::le<std::int32_t>(1);
  EXPECT_EQ(m.status_of(TransferRequest{0x0011, pos}), Status::permission_error) << "only 3xxx is writable";
  EXPECT_EQ(m.status_of(TransferRequest{0x3011, pos}), Status::parameter_count_error) << "speed is UINT16";
  EXPECT_EQ(m.status_of(TransferRequest{0x3011, RawMaster::le<std::uint16_t>(101)}),
            Status::parameter_data_error);
  EXPECT_EQ(m.status_of(ExecuteRequest{2, 9, 0xFF}), Status::parameter_data_error) << "F3 not parameterized";
  EXPECT_EQ(m.status_of(ExecuteRequest{0, 10, 0xFF}), Status::parameter_data_error) << "direction 0..9";
  EXPECT_EQ(m.status_of(ExecuteRequest{0, 9, 2}), Status::parameter_data_error);
  EXPECT_EQ(m.status_of(StopRequest{14, 0}), Status::parameter_data_error) << "no function 15";
  EXPECT_EQ(m.status_of(CyclicRequest{5, {}}), Status::parameter_data_error) << "CyclicObj 1..5 only";
  const std::uint8_t junk[] = {1};
  EXPECT_EQ(m.status_of(CyclicRequest{0, junk}), Status::parameter_count_error)
      << "object 1 has no write IDs";
  // A damaged request: CSE for its command.
  auto rg = *wire::parse_hex("52 47 11 00 2c 31");
  EXPECT_EQ(m.send_raw(rg, {Command::get, true})->status, Status::checksum_error);
  // An unknown command: ICE.
  const auto unknown = *wire::parse_hex("52 5a 00 00");
  m.stream.expect({static_cast<Command>('Z'), false});
  (void)m.sim.master().write(unknown);
  m.idle(10ms);
  std::array<std::uint8_t, 16> buf{};
  const auto r = m.sim.master().read(buf);
  ASSERT_EQ(r.count, 5u);
  EXPECT_EQ(buf[1], 'Z');
  EXPECT_EQ(buf[2], 0x83);
}

TEST(ScuEmulator, DiscardsAPartialRequestAfterOneSecondOfSilence) {
  RawMaster m;
  const auto ro = *wire::parse_hex("52 4f 00 5c 2d");
  (void)m.sim.master().write(std::span(ro).first(2));
  m.idle(1100ms);
  EXPECT_EQ(m.emulator.discarded_partial_requests(), 1u);
  EXPECT_EQ(m.send_raw(ro, {Command::open, false})->status, Status::ack);
}

TEST(ScuEmulator, CyclicObjectWritesAndReads) {
  RawMaster m;
  m.open_remote();
  // CyclicObj 2: write remote position A2, read position A2 and status group.
  std::vector<std::uint8_t> obj;
  const std::uint16_t ids[] = {0x3022, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF,
                               0x0012, 0x0170, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF};
  for (const auto id : ids) {
    const auto b = RawMaster::le(id);
    obj.insert(obj.end(), b.begin(), b.end());
  }
  ASSERT_EQ(m.status_of(TransferRequest{0x3002, obj}), Status::ack);
  const auto pos = RawMaster::le<std::int32_t>(-200);
  const auto a = m.send(CyclicRequest{1, pos});
  ASSERT_TRUE(a);
  ASSERT_EQ(a->status, Status::ack);
  ASSERT_EQ(a->data.size(), 4u + 6u);
  // A1 rests at 0: present, limit signal, in position reached, stroke recorded.
  EXPECT_EQ(a->data[4], 0xA3);
  EXPECT_EQ(a->data[6], 0) << "A3 not present";
  EXPECT_EQ(m.send(GetRequest{0x3022})->data, pos);
  EXPECT_EQ(m.send(GetRequest{0x3001})->data.size(), 24u);
  // A read-only ID as write data is refused.
  obj[0] = 0x11;
  obj[1] = 0x00;
  EXPECT_EQ(m.status_of(TransferRequest{0x3003, obj}), Status::parameter_data_error);
}

TEST(ScuEmulator, ReadsTheDataListWithPlausibleValues) {
  RawMaster m;
  m.open_remote();
  EXPECT_EQ(m.send(GetRequest{0x0010})->data.size(), 24u);
  EXPECT_EQ(m.send(GetRequest{0x2001})->data.size(), 104u);
  EXPECT_EQ(m.send(GetRequest{0x2000})->data.size(), 624u) << "the largest group fits a reply";
  EXPECT_EQ(m.send(GetRequest{0x0002})->data.size(), 36u);
  EXPECT_EQ(m.send(GetRequest{0x00E1})->data, std::vector<std::uint8_t>{0x06})
      << "released, not initialised: no run into the retracted end since power-up";
  EXPECT_EQ(m.send(GetRequest{0x3011})->data, RawMaster::le<std::uint16_t>(100)) << "default speed";
  EXPECT_EQ(m.send(GetRequest{0x3021})->data, RawMaster::le<std::int32_t>(4000))
      << "Memory 1 = 20 % of 200 mm";
}

TEST(ScuEmulator, FaultInjectionSetsTheManualsBitsAndStops) {
  RawMaster m;
  m.open_remote();
  ASSERT_EQ(m.status_of(TransferRequest{0x3021, RawMaster::le<std::int32_t>(15000)}), Status::ack);
  ASSERT_EQ(m.status_of(ExecuteRequest{0, 9, kFastStartStop}), Status::ack);
  m.idle(50ms);
  ASSERT_EQ(m.status_of(CyclicRequest{}), Status::ack);
  EXPECT_TRUE(m.emulator.status1(1).motion_active);
  m.emulator.inject_actuator_fault(1);
  EXPECT_FALSE(m.emulator.status1(1).motion_active);
  EXPECT_TRUE(m.emulator.error_word().actuator_fault(1));
  m.emulator.inject_over_current();
  EXPECT_TRUE(m.emulator.error_word().over_current());
  EXPECT_EQ(m.send(GetRequest{0x00D2})->data, RawMaster::le<std::uint32_t>(1u << 14))
      << "history keeps the earlier word";
  // The next motion resets bits 14..21.
  ASSERT_EQ(m.status_of(ExecuteRequest{0, 9, kFastStartStop}), Status::ack);
  EXPECT_FALSE(m.emulator.error_word().any());
  // A jammed actuator does not report motion.
  m.emulator.actuator(1).set_blocked(true);
  m.idle(10ms);
  EXPECT_FALSE(m.emulator.status1(1).motion_active);
  // Lost and late replies.
  m.emulator.drop_next_replies(1);
  EXPECT_FALSE(m.send(CyclicRequest{}).has_value());
  m.emulator.set_reply_delay(50ms);
  const auto t0 = m.clock.now();
  EXPECT_TRUE(m.send(CyclicRequest{}).has_value());
  EXPECT_GE(m.clock.now() - t0, 50ms);
}

TEST(ScuEmulator, ALastingActuatorFaultStopsEveryMotionStartUntilItIsGone) {
  RawMaster m;
  m.open_remote();
  ASSERT_EQ(m.status_of(TransferRequest{0x3021, RawMaster::le<std::int32_t>(15000)}), Status::ack);
  m.emulator.set_actuator_fault(1, true);
  EXPECT_TRUE(m.emulator.error_word().actuator_fault(1));
  // The RE is accepted (the manual has no refusal for it) but the fault comes back at once.
  ASSERT_EQ(m.status_of(ExecuteRequest{0, 9, kFastStartStop}), Status::ack);
  m.idle(50ms);
  EXPECT_FALSE(m.emulator.actuator(1).active());
  EXPECT_FALSE(m.emulator.status1(1).motion_active);
  EXPECT_TRUE(m.emulator.error_word().actuator_fault(1));
  EXPECT_NEAR(m.emulator.actuator(1).position_mm(), 0.0, 1e-9);
  EXPECT_FALSE(m.emulator.error_word().actuator_fault(2)) << "only the faulty actuator";

  m.emulator.set_actuator_fault(1, false);  // repaired: the next motion resets the bit and moves
  EXPECT_TRUE(m.emulator.error_word().actuator_fault(1)) << "the bit stays until the next motion";
  ASSERT_EQ(m.status_of(ExecuteRequest{0, 9, kFastStartStop}), Status::ack);
  m.idle(50ms);
  EXPECT_FALSE(m.emulator.error_word().actuator_fault(1));
  EXPECT_TRUE(m.emulator.actuator(1).active());
  EXPECT_THROW(m.emulator.set_actuator_fault(3, true), std::out_of_range);
  // Every way a test names an actuator the config does not have is refused alike.
  EXPECT_THROW((void)m.emulator.actuator(3), std::out_of_range);
  EXPECT_THROW((void)std::as_const(m.emulator).actuator(0), std::out_of_range);
  EXPECT_THROW(m.emulator.inject_actuator_fault(7), std::out_of_range);
  EXPECT_FALSE(m.emulator.has_actuator(3));
  EXPECT_TRUE(m.emulator.has_actuator(2));
}

TEST(ScuEmulator, SynchronizedFunctionMovesTogetherAndGuardsThePositionDifference) {
  auto config = scp11_emulator(2, testing::test_physics(), 100.0);
  config.actuators[1].physics.max_speed_mm_s = 10.0;
  config.functions[2] = FunctionDef{true, 0b11, true};  // F3 moves A1 and A2 synchronized
  link::VirtualClock clock;
  link::SimLink sim(clock, link::line_8n1(38400));
  Emulator emu(sim.device(), config);
  auto send = [&](const Request& r) {
    RequestBytes b;
    ASSERT_TRUE(encode_request(r, b));
    (void)sim.master().write(b.view());
    cellctl::testing::run_for(clock, 1ms, 20ms, [&](link::TimePoint t) { emu.poll(t); });
  };
  send(OpenRequest{0});
  send(CyclicRequest{});
  send(ExecuteRequest{2, static_cast<std::uint8_t>(Direction::out), kFastStartStop});
  EXPECT_DOUBLE_EQ(emu.actuator(1).velocity_mm_s(), 10.0) << "at the pace of the slower actuator";
  EXPECT_DOUBLE_EQ(emu.actuator(2).velocity_mm_s(), 10.0);
  emu.inject_position_difference(3);
  EXPECT_TRUE(emu.error_word().position_difference());
  EXPECT_FALSE(emu.actuator(1).active());
  EXPECT_FALSE(emu.actuator(2).active());
}

}  // namespace
}  // namespace cellctl::scu
