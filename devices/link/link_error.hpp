#pragma once
// Raised only while opening a link (load time), never from read/write: names the port and the cause.

#include <stdexcept>
#include <string>

namespace cellctl::link {

class LinkError : public std::runtime_error {
 public:
  // `cause`: the errno the open failed with (0 when none), for callers that advise by it.
  explicit LinkError(const std::string& what, int cause = 0) : std::runtime_error(what), cause_(cause) {}
  [[nodiscard]] int cause() const noexcept { return cause_; }

 private:
  int cause_;
};

}  // namespace cellctl::link
