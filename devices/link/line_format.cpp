#include "link/line_format.hpp"

#include <fmt/format.h>

namespace cellctl::link {

std::string LineFormat::describe() const {
  const char p = parity == Parity::none ? 'N' : parity == Parity::even ? 'E' : 'O';
  return fmt::format("{} {}{}{}", baud, data_bits, p, stop_bits);
}

}  // namespace cellctl::link
