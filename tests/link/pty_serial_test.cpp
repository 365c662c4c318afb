// SerialLink against a real pseudo-terminal made by PtyPair: transparency of all 256 byte values in
// both directions (a tty left in cooked mode would eat or translate some), exclusive open, and the
// errors an operator sees for a missing or busy port.

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numeric>
#include <thread>
#include <vector>

#include "link/link_error.hpp"
#include "link/pty_pair.hpp"
#include "link/serial_link.hpp"

namespace cellctl::link {
namespace {

// Reads from `from` until `n` bytes came or 2 s passed: waits for a condition, with a bound.
std::vector<std::uint8_t> receive(Link& from, std::size_t n) {
  std::vector<std::uint8_t> got;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  std::array<std::uint8_t, 256> buf{};
  while (got.size() < n && std::chrono::steady_clock::now() < deadline) {
    auto r = from.read(buf);
    EXPECT_TRUE(r.ok());
    got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(r.count));
    if (r.count == 0) std::this_thread::yield();
  }
  return got;
}

std::vector<std::uint8_t> all_byte_values() {
  std::vector<std::uint8_t> v(256);
  std::iota(v.begin(), v.end(), std::uint8_t{0});
  return v;
}

TEST(PtySerial, EveryByteValuePassesBothWays) {
  PtyPair pty("test");
  auto serial = SerialLink::open(pty.peer_path(), line_8n1(38400));
  EXPECT_FALSE(serial->modem_lines_held()) << "a pty has no modem lines";
  const auto bytes = all_byte_values();

  ASSERT_EQ(serial->write(bytes).count, bytes.size());
  EXPECT_EQ(receive(pty.device(), bytes.size()), bytes);

  ASSERT_EQ(pty.device().write(bytes).count, bytes.size());
  EXPECT_EQ(receive(*serial, bytes.size()), bytes);
}

TEST(PtySerial, PublishesAndRemovesASymlink) {
  const auto link_path =
      std::filesystem::temp_directory_path() / ("cellctl-test-" + std::to_string(::getpid()));
  {
    PtyPair pty("test", link_path);
    ASSERT_TRUE(std::filesystem::is_symlink(link_path));
    EXPECT_EQ(std::filesystem::read_symlink(link_path).string(), pty.peer_path());
    auto serial = SerialLink::open(link_path.string(), line_8n1(38400));
    const std::vector<std::uint8_t> hello{0x52, 0x4f, 0x00};
    ASSERT_EQ(serial->write(hello).count, 3u);
    EXPECT_EQ(receive(pty.device(), 3), hello);
  }
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(link_path)));
}

TEST(PtySerial, RefusesToReplaceARegularFile) {
  const auto path = std::filesystem::temp_directory_path() / ("cellctl-file-" + std::to_string(::getpid()));
  std::ofstream(path) << "precious";
  EXPECT_THROW(PtyPair("test", path), LinkError);
  EXPECT_TRUE(std::filesystem::is_regular_file(path));
  std::filesystem::remove(path);
}

TEST(PtySerial, MissingPortIsNamedInTheError) {
  try {
    (void)SerialLink::open("/dev/cellctl-no-such-port", line_8n1(38400));
    FAIL() << "expected LinkError";
  } catch (const LinkError& e) {
    EXPECT_STREQ(e.what(), "serial port /dev/cellctl-no-such-port does not exist");
  }
}

TEST(PtySerial, SecondOpenIsRefusedAsBusy) {
  PtyPair pty("test");
  auto first = SerialLink::open(pty.peer_path(), line_8n1(38400));
  try {
    (void)SerialLink::open(pty.peer_path(), line_8n1(38400));
    FAIL() << "expected LinkError";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("in use by another process"), std::string::npos) << e.what();
  }
}

TEST(PtySerial, AnEvenParityLineOpensAgainAfterClosing) {
  // PROFIBUS commissioning opens the encoder's pty once per command: each open must work.
  PtyPair pty("test");
  for (int i = 0; i < 3; ++i) {
    auto s = SerialLink::open(pty.peer_path(), line_8e1(19200));
    const std::vector<std::uint8_t> b{0x10, 0x05};
    ASSERT_EQ(s->write(b).count, 2u);
    EXPECT_EQ(receive(pty.device(), 2), b);
  }
}

TEST(PtySerial, UnsupportedBaudIsRefused) {
  PtyPair pty("test");
  EXPECT_THROW((void)SerialLink::open(pty.peer_path(), line_8n1(12345)), LinkError);
}

TEST(PtySerial, PeerCanReopenAfterClosing) {
  PtyPair pty("test");
  { auto s = SerialLink::open(pty.peer_path(), line_8n1(38400)); }
  auto again = SerialLink::open(pty.peer_path(), line_8n1(38400));
  const std::vector<std::uint8_t> b{0x02, 0x03};
  ASSERT_EQ(pty.device().write(b).count, 2u);
  EXPECT_EQ(receive(*again, 2), b);
}

TEST(PtySerial, ReadsOnlyWhatHasArrivedAndNothingFromAnEmptyLine) {
  PtyPair pty("test");
  auto s = SerialLink::open(pty.peer_path(), line_8n1(38400));
  std::array<std::uint8_t, 16> buf{};
  const auto empty = s->read(buf);
  EXPECT_TRUE(empty.ok());
  EXPECT_EQ(empty.count, 0u);
  const std::vector<std::uint8_t> b{0x01, 0x02, 0x03};
  ASSERT_EQ(pty.device().write(b).count, 3u);
  EXPECT_EQ(receive(*s, 3), b) << "bytes that arrive are read (FIONREAD counts them)";
  EXPECT_EQ(s->read(buf).count, 0u);
}

TEST(PtySerial, APortWhoseOtherSideWentAwayReadsClosed) {
  auto pty = std::make_unique<PtyPair>("test");
  auto s = SerialLink::open(pty->peer_path(), line_8n1(38400));
  pty.reset();  // the emulator's side closes: the kernel hangs the terminal up, as on an unplugged adapter
  std::array<std::uint8_t, 16> buf{};
  const auto r = s->read(buf);
  EXPECT_EQ(r.status, IoStatus::closed);
  EXPECT_EQ(r.error_number, EIO);
}

}  // namespace
}  // namespace cellctl::link
