#pragma once
// Raised only while opening a link (load time), never from read/write: names the port and the cause.

#include <stdexcept>
#include <string>

namespace cellctl::link {

class LinkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cellctl::link
