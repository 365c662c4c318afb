#pragma once
// Who owns a publish_as path: `cellctl emulate` holds an exclusive flock on "<publish_as>.lock" for as
// long as it runs (the kernel drops it when the process dies, however it dies). A second emulation
// that finds the lock held refuses, naming the path and the owner's process id, instead of replacing
// the first one's link (and deleting it when it ends). A lock left by a dead process is taken over.

#include <filesystem>
#include <optional>
#include <string>

namespace cellctl::cli {

class PublishLock {
 public:
  // Throws link::LinkError with the reason when another live process holds the lock, or when the
  // lock file cannot be created.
  explicit PublishLock(std::filesystem::path publish_as);
  ~PublishLock();

  // Whether a live `cellctl emulate` publishes at `publish_as`: its process id as it wrote it (empty
  // when unreadable), or nothing when no live process holds the lock.
  [[nodiscard]] static std::optional<std::string> holder(const std::filesystem::path& publish_as);
  PublishLock(const PublishLock&) = delete;
  PublishLock& operator=(const PublishLock&) = delete;

 private:
  std::filesystem::path path_;
  int fd_ = -1;
};

}  // namespace cellctl::cli
