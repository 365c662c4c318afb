#include "cli/publish_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <string>

#include "link/link_error.hpp"

namespace cellctl::cli {
namespace {

// The owner's process id as it wrote it into the lock file (empty when unreadable).
std::string owner_of(int fd) {
  std::array<char, 32> buf{};
  const ssize_t n = ::pread(fd, buf.data(), buf.size() - 1, 0);
  if (n <= 0) return {};
  std::string pid(buf.data(), static_cast<std::size_t>(n));
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  return pid;
}

// The locked descriptor still names the file at `path` (not one unlinked by its last owner meanwhile).
bool still_at(int fd, const std::filesystem::path& path) {
  struct stat held {};
  struct stat named {};
  return ::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
         held.st_dev == named.st_dev;
}

// The exclusive lock, waiting up to 100 ms for it: holder() of another process takes a shared lock
// for a moment to see whether the lock is held, and must not make an emulation starting just then
// refuse. A live emulation holds it far longer. False with errno set when it stays held.
bool lock_soon(int fd) {
  for (int attempt = 0;; ++attempt) {
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return true;
    if (errno != EWOULDBLOCK || attempt == 20) return false;
    ::usleep(5000);
  }
}

}  // namespace

std::optional<std::string> PublishLock::holder(const std::filesystem::path& publish_as) {
  const std::string path = publish_as.string() + ".lock";
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::optional<std::string> owner;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) owner = owner_of(fd);
  ::close(fd);  // also releases the shared lock when it was free
  return owner;
}

PublishLock::PublishLock(std::filesystem::path publish_as) : path_(publish_as.string() + ".lock") {
  for (;;) {
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0)
      throw link::LinkError(fmt::format("cannot publish at {}: lock file {}: {}", publish_as.string(),
                                        path_.string(), std::strerror(errno)));
    if (!lock_soon(fd_)) {
      const int err = errno;
      const std::string owner = owner_of(fd_);
      ::close(fd_);
      fd_ = -1;
      if (err == EWOULDBLOCK)
        throw link::LinkError(fmt::format(
            "{} is published by another live `cellctl emulate`{}; refusing to replace its link (end that "
            "emulation first, or give this cell another publish_as)",
            publish_as.string(), owner.empty() ? "" : " (pid " + owner + ")"));
      throw link::LinkError(fmt::format("cannot lock {}: {}", path_.string(), std::strerror(err)));
    }
    if (still_at(fd_, path_)) break;
    ::close(fd_);  // its previous owner removed it between our open and our lock: take the new one
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The pid is only for the message of a refused second emulation; the lock itself holds.
  }
}

PublishLock::~PublishLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still held: a waiting process re-checks still_at() and retries
  ::close(fd_);
}

}  // namespace cellctl::cli
