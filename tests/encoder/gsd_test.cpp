// The shipped GSD file describes the emulated encoder the code implements: ident number, one module
// per functionality with our configuration identifiers, and default User_Prm_Data equal to what
// encode_user_prm() writes for the default parameters.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "encoder/functionality.hpp"
#include "encoder/parameters.hpp"

namespace cellctl::encoder {
namespace {

std::vector<std::uint8_t> hex_list(const std::string& text) {
  std::vector<std::uint8_t> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(static_cast<std::uint8_t>(std::stoul(item, nullptr, 16)));
  return out;
}

std::string trim(std::string s) {
  s.erase(0, s.find_first_not_of(" \t\r"));
  s.erase(s.find_last_not_of(" \t\r") + 1);
  return s;
}

struct GsdModule {
  std::vector<std::uint8_t> cfg;
  std::vector<std::uint8_t> prm_const;
};

struct Gsd {
  unsigned long ident = 0;
  std::map<std::string, GsdModule> modules;
};

Gsd read_gsd() {
  std::ifstream in(CELLCTL_ENCODER_GSD);
  EXPECT_TRUE(in) << CELLCTL_ENCODER_GSD;
  Gsd gsd;
  std::string line;
  std::string module;
  while (std::getline(in, line)) {
    line = trim(line.substr(0, line.find(';')));
    if (line.rfind("Ident_Number", 0) == 0)
      gsd.ident = std::stoul(trim(line.substr(line.find('=') + 1)), nullptr, 16);
    if (line.rfind("Module", 0) == 0 && line.find('"') != std::string::npos) {
      const auto close = line.find('"', line.find('"') + 1);
      module = line.substr(line.find('"') + 1, close - line.find('"') - 1);
      gsd.modules[module].cfg = hex_list(trim(line.substr(close + 1)));
    }
    if (line.rfind("Ext_User_Prm_Data_Const(0)", 0) == 0)
      gsd.modules[module].prm_const = hex_list(trim(line.substr(line.find('=') + 1)));
  }
  return gsd;
}

TEST(Gsd, IdentAndModulesMatchTheCode) {
  const Gsd gsd = read_gsd();
  EXPECT_EQ(gsd.ident, kIdentNumber);
  const std::pair<const char*, Functionality> expected[] = {
      {"Class 1 Multiturn", Functionality::class1},
      {"Class 2 Multiturn", Functionality::class2},
      {"Scancon 2.1 Multiturn", Functionality::scancon21},
      {"Scancon 2.2 Multiturn", Functionality::scancon22},
      {"Scancon 3.0 Multiturn", Functionality::scancon30},
  };
  ASSERT_EQ(gsd.modules.size(), 5u);
  for (const auto& [name, f] : expected) {
    ASSERT_TRUE(gsd.modules.contains(name)) << name;
    const auto& m = gsd.modules.at(name);
    const auto ids = config_identifiers(f);
    EXPECT_EQ(m.cfg, std::vector<std::uint8_t>(ids.begin(), ids.end())) << name;
    EncoderParameters p;
    p.functionality = f;
    std::array<std::uint8_t, 64> prm{};
    const std::size_t n = encode_user_prm(p, prm);
    EXPECT_EQ(m.prm_const,
              std::vector<std::uint8_t>(prm.begin(), prm.begin() + static_cast<std::ptrdiff_t>(n)))
        << name;
  }
}

}  // namespace
}  // namespace cellctl::encoder
