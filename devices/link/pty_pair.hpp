#pragma once
// A pseudo-terminal for an emulator: the emulator reads and writes the master side (device()), and
// any program — this one through SerialLink, or minicom, or socat — opens peer_path() as if it were
// the device's serial port. Optionally the peer is published as a symlink at a fixed path so that
// a config file can name it before it exists.

#include <filesystem>
#include <optional>
#include <string>

#include "link/link.hpp"

namespace cellctl::link {

class PtyPair {
 public:
  // Throws LinkError when no pty can be had or the symlink path holds something else than a symlink.
  explicit PtyPair(std::string name, std::optional<std::filesystem::path> symlink = std::nullopt);
  ~PtyPair();
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  [[nodiscard]] Link& device() noexcept { return device_; }
  [[nodiscard]] const std::string& peer_path() const noexcept { return peer_path_; }
  [[nodiscard]] const std::optional<std::filesystem::path>& symlink() const noexcept { return symlink_; }

 private:
  class MasterSide final : public Link {
   public:
    IoResult read(std::span<std::uint8_t> buffer) override;
    IoResult write(std::span<const std::uint8_t> bytes) override;
    [[nodiscard]] std::string describe() const override { return name; }
    int fd = -1;
    std::string name;
  };

  MasterSide device_;
  int held_peer_fd_ = -1;  // keeps the pty alive (no EIO on the master) while no client has it open
  std::string peer_path_;
  std::optional<std::filesystem::path> symlink_;
};

}  // namespace cellctl::link
