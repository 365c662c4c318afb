#include "encoder/eeprom_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cellctl::encoder {

NonVolatile load_eeprom(const std::filesystem::path& path) {
  NonVolatile nv;
  std::ifstream in(path);
  if (!in) return nv;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    std::istringstream words(line);
    std::string key;
    long long value = 0;
    std::string word;
    words >> key;
    const auto bad = [&](const char* rule) {
      return std::runtime_error(fmt::format("{}:{}: {}: {}", path.string(), number, key, rule));
    };
    if (key == "code_sequence") {
      words >> word;
      if (word != "cw" && word != "ccw") throw bad("must be cw or ccw");
      nv.code_sequence = word == "ccw" ? CodeSequence::ccw : CodeSequence::cw;
      continue;
    }
    if (!(words >> value)) throw bad("expected a number");
    if (key == "offset" && value >= INT32_MIN && value <= INT32_MAX)
      nv.offset = static_cast<std::int32_t>(value);
    else if (key == "taught_units" && value >= 0 && value <= UINT32_MAX)
      nv.taught_units = static_cast<std::uint32_t>(value);
    else if (key == "address" && value >= 0 && value <= 126)
      nv.address = static_cast<std::uint8_t>(value);
    else
      throw bad("unknown key or value out of range");
  }
  return nv;
}

bool save_eeprom(const std::filesystem::path& path, const NonVolatile& nv) noexcept {
  try {
    const auto tmp = std::filesystem::path(path.string() + ".tmp");
    {
      std::ofstream out(tmp, std::ios::trunc);
      out << "offset " << nv.offset << "\ncode_sequence "
          << (nv.code_sequence == CodeSequence::ccw ? "ccw" : "cw") << "\ntaught_units " << nv.taught_units
          << "\naddress " << unsigned{nv.address} << "\n";
      if (!out) return false;
    }
    std::filesystem::rename(tmp, path);
    return true;
  } catch (...) {
    return false;
  }
}

}  // namespace cellctl::encoder
